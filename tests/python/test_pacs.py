"""mvw.pacs against `mvw pacs find --json` on a real Orthanc (tests/support/orthanc) holding
twelve slices of the Cranium CT: the same matches, a study's series, the verified cache's
folder for mvw.read, and the errors (an unknown study, a server that does not answer)."""
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
    for f in sorted((data / "cranium" / "dicom").iterdir())[:12]:
        shutil.copy(f, ct / f.name)
    subprocess.run(["bash", str(ORTHANC), "start", str(work / "orthanc")], check=True,
                   capture_output=True)
    try:
        env = {}
        for line in (work / "orthanc" / "orthanc.env").read_text().splitlines():
            key, _, value = line.removeprefix("export ").partition("=")
            env[key] = value.strip("'\"")
        subprocess.run(["bash", str(ORTHANC), "upload", str(work / "orthanc"), str(ct)],
                       check=True, capture_output=True)
        yield env["ORTHANC_WEB"], env["ORTHANC_DIMSE"], work
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
    web, dimse, work = server
    for url in (web, dimse):
        studies = mvw.pacs.find(url, patient_name="*")
        assert studies == cli_find(url, "--patient-name", "*")
        assert len(studies) == 1
        uid = studies[0]["StudyInstanceUID"]
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


def test_errors(server):
    web, _, work = server
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
