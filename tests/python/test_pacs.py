"""mvw.pacs against `mvw pacs find --json` on a real Orthanc (tests/support/orthanc) holding
twelve slices of the Cranium CT and one instance mvw cannot read: the same matches, a study's
series, the verified cache's folder for mvw.read, the series read into a Volume (read=True) with
a study's quarantine of a cached file that fails to read, and the errors (an unknown study, a
server that does not answer)."""
import json
import os
import pathlib
import shutil
import signal
import socket
import subprocess

import numpy as np
import pytest

import mvw

ORTHANC = pathlib.Path(__file__).resolve().parents[1] / "support" / "orthanc"


@pytest.fixture(scope="module")
def server(data, tmp_path_factory):
    work = tmp_path_factory.mktemp("pacs")
    ct = work / "ct"
    ct.mkdir()
    files = sorted((data / "cranium" / "dicom").iterdir())
    for f in files[:12]:
        shutil.copy(f, ct / f.name)
    # Whole and verified on receipt, yet mvw cannot read it (Bits Allocated 12): a read that
    # fails on a cached file, as a decoder's refusal would (tests/cli/pacs-cache's).
    import pydicom
    from pydicom.uid import generate_uid
    unreadable = work / "unreadable"
    unreadable.mkdir()
    u = pydicom.dcmread(files[0])
    u.StudyInstanceUID, u.SeriesInstanceUID = generate_uid(), generate_uid()
    u.SOPInstanceUID = u.file_meta.MediaStorageSOPInstanceUID = generate_uid()
    u.BitsAllocated = 12
    u.save_as(unreadable / "u.dcm")
    subprocess.run(["bash", str(ORTHANC), "start", str(work / "orthanc")], check=True,
                   capture_output=True)
    try:
        env = {}
        for line in (work / "orthanc" / "orthanc.env").read_text().splitlines():
            key, _, value = line.removeprefix("export ").partition("=")
            env[key] = value.strip("'\"")
        subprocess.run(["bash", str(ORTHANC), "upload", str(work / "orthanc"), str(ct),
                        str(unreadable)], check=True, capture_output=True)
        yield env["ORTHANC_WEB"], env["ORTHANC_DIMSE"], work, (u.StudyInstanceUID,
                                                                u.SeriesInstanceUID)
    finally:
        # Killed outright (its storage is thrown away): SIGTERM costs Orthanc about 5 s.
        pid = work / "orthanc" / "orthanc.pid"
        if pid.exists():
            try:
                os.kill(int(pid.read_text()), signal.SIGKILL)
            except (ProcessLookupError, ValueError):
                pass
        subprocess.run(["bash", str(ORTHANC), "stop", str(work / "orthanc")], capture_output=True)


def cli_find(*args):
    done = subprocess.run([os.environ["MVW"], "pacs", "find", *args, "--json"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return [json.loads(line) for line in done.stdout.splitlines()]


def test_find_equals_cli_and_get_reads(server, data):
    web, dimse, work, (unreadable_study, _) = server
    for url in (web, dimse):
        studies = mvw.pacs.find(url, patient_name="*")
        assert studies == cli_find(url, "--patient-name", "*")
        assert len(studies) == 2
        uid = next(s["StudyInstanceUID"] for s in studies
                   if s["StudyInstanceUID"] != unreadable_study)
        series = mvw.pacs.find(url, study=uid)
        assert series == cli_find(url, "--study", uid)
        assert series[0]["NumberOfSeriesRelatedInstances"] == "12"
    folder = mvw.pacs.get(web, uid, series[0]["SeriesInstanceUID"], cache=work / "cache")
    assert isinstance(folder, pathlib.Path) and folder.is_relative_to(work / "cache")
    volume = mvw.read(folder)
    assert volume.shape[2] == 12
    # The same slices as the files the server was given.
    local = mvw.read(work / "ct")
    assert np.array_equal(volume.array, local.array)
    assert np.array_equal(volume.affine_lps, local.affine_lps)
    # read=True: the same series read into a Volume, from the cache.
    cached = mvw.pacs.get(web, uid, series[0]["SeriesInstanceUID"], cache=work / "cache",
                          read=True)
    assert isinstance(cached, mvw.Volume) and cached.path == str(folder)
    assert np.array_equal(cached.array, local.array)
    assert np.array_equal(cached.affine_lps, local.affine_lps)


def test_get_read_quarantines_a_cached_file_that_fails_to_read(server):
    """As a study reads its PACS series: the series whose cached file mvw cannot read moves into
    the quarantine, the error names the file there, and the next call retrieves it again."""
    web, _, work, (study, series) = server
    cache = work / "quarantine-cache"
    for attempt in (1, 2):
        with pytest.raises(mvw.InputError, match="unsupported BitsAllocated 12") as caught:
            mvw.pacs.get(web, study, series, cache=cache, read=True)
        assert pathlib.Path(caught.value.file).is_relative_to(cache / "quarantine")
        assert "retrieved again on the next run" in str(caught.value)
        assert len(list((cache / "quarantine").iterdir())) == attempt
    # The folder alone (read=False) is not read, so it stays in the cache.
    folder = mvw.pacs.get(web, study, series, cache=cache)
    assert folder.is_relative_to(cache) and len(list(folder.glob("*.dcm"))) == 1


def test_errors(server):
    web, _, work, _ = server
    with pytest.raises(mvw.InputError, match="has no study 1.2.3.4"):
        mvw.pacs.find(web, study="1.2.3.4")
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(mvw.ServiceError, match=f"127.0.0.1:{port}"):
        mvw.pacs.find(f"http://127.0.0.1:{port}/dicom-web", connect_timeout=2)
    with pytest.raises(TypeError):
        mvw.pacs.find(web, study=42)
    with pytest.raises(ValueError, match="calling_aet"):
        mvw.pacs.find(web, calling_aet="")


def test_get_and_find_release_the_gil_while_the_server_is_silent(tmp_path, releases_gil):
    """A server that takes the connection and never answers: the call waits out its read
    time-out with the GIL released, then raises mvw.ServiceError naming the server."""
    with socket.socket() as silent:  # listening: the kernel accepts, nobody answers
        silent.bind(("127.0.0.1", 0))
        silent.listen()
        url = f"http://127.0.0.1:{silent.getsockname()[1]}/dicom-web"
        with pytest.raises(mvw.ServiceError, match=f"127.0.0.1:{silent.getsockname()[1]}"):
            releases_gil(lambda: mvw.pacs.get(url, "1.2.3", "1.2.3.4", cache=tmp_path,
                                              read_timeout=1), "mvw.pacs.get")
        with pytest.raises(mvw.ServiceError):
            releases_gil(lambda: mvw.pacs.find(url, patient_name="*", read_timeout=1),
                         "mvw.pacs.find")
