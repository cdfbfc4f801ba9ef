"""Every error type: mvw.InputError (a ValueError naming the file), mvw.ServiceError (a
ConnectionError naming the server), TypeError for a bad argument type; nothing aborts."""
import os
import shutil
import socket
import subprocess
import sys

import numpy as np
import pytest

import mvw


def test_exception_classes():
    assert issubclass(mvw.InputError, ValueError)
    assert issubclass(mvw.ServiceError, ConnectionError)
    assert mvw.InputError.__doc__ and mvw.ServiceError.__doc__


def test_missing_file_is_an_input_error_naming_it(tmp_path):
    missing = tmp_path / "nothing.nii.gz"
    with pytest.raises(mvw.InputError) as caught:
        mvw.read(missing)
    assert str(missing) in str(caught.value)
    assert caught.value.file == str(missing)
    assert "no such file" in caught.value.problem


def test_bad_file_is_an_input_error_naming_it(tmp_path):
    bad = tmp_path / "bad.nii"
    bad.write_bytes(b"\0" * 400)
    with pytest.raises(ValueError) as caught:  # catchable as the built-in base
        mvw.read(bad)
    assert isinstance(caught.value, mvw.InputError)
    assert caught.value.file == str(bad) and str(bad) in str(caught.value)


def test_frame_out_of_range_is_an_input_error(data):
    path = data / "nibabel" / "example4d.nii.gz"
    with pytest.raises(mvw.InputError, match="example4d"):
        mvw.read(path, frame=1000)
    with pytest.raises(mvw.InputError, match="'mean'"):
        mvw.read(path, frame="middle")


def _closed_port():
    with socket.socket() as s:  # a port nobody listens on: the connection is refused
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_unreachable_pacs_is_a_service_error_naming_it(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))  # the PACS cache, not ~/.cache
    server = f"http://127.0.0.1:{_closed_port()}/dicom-web"
    config = tmp_path / "study.json"
    config.write_text('{ "anatomical": { "pacs": "%s", "study": "1.2.3", "series": "1.2.3.4" } }'
                      % server)
    with pytest.raises(mvw.ServiceError) as caught:
        mvw.read(config)
    assert isinstance(caught.value, ConnectionError)
    assert server.split("/dicom-web")[0].split("//")[1] in str(caught.value)


def test_bad_argument_types_are_type_errors(data):
    with pytest.raises(TypeError):
        mvw.read(42)
    with pytest.raises(TypeError):
        mvw.read(data / "nibabel" / "example4d.nii.gz", frame=1.5)
    with pytest.raises(TypeError):
        mvw.stats("not a volume", sphere=(0, 0, 0, 1))
    with pytest.raises(TypeError):
        mvw.stats(mvw.read(data / "derived" / "pet_like.nii.gz"), sphere="centre")
    with pytest.raises(TypeError, match="dtype"):
        mvw.Volume.from_array(np.zeros((2, 2, 2), np.int64), affine_lps=np.eye(4))
    with pytest.raises(TypeError, match="exactly one of affine_lps and affine_ras"):
        mvw.Volume.from_array(np.zeros((2, 2, 2), np.int16))
    with pytest.raises(TypeError, match="4 x 4"):
        mvw.Volume.from_array(np.zeros((2, 2, 2), np.int16), affine_lps=np.eye(3))


def test_an_empty_axis_is_a_value_error_not_an_abort():
    # A Volume's constructor would abort the interpreter on an empty axis: refused before it.
    with pytest.raises(ValueError, match="axis 0 of the array has 0 elements"):
        mvw.Volume.from_array(np.zeros((0, 4, 4), np.int16), affine_lps=np.eye(4))
    with pytest.raises(ValueError, match="axis 3 of the array has 0 elements"):
        mvw.Volume.from_array(np.zeros((2, 2, 2, 0), np.float32), affine_lps=np.eye(4))


def test_a_failing_decoder_is_an_input_error_and_the_session_goes_on(data, monkeypatch):
    # Compressed pixel data is decoded by the child mvw-decoder; a child that fails (here
    # /bin/false in its place: it ends before answering) is the file's error, not the
    # interpreter's, and the next read decodes with the real helper.
    jpeg = data / "pydicom" / "test_files" / "SC_rgb_jpeg_dcmtk.dcm"
    expected = mvw.read(jpeg).array.copy()
    monkeypatch.setenv("MVW_DECODER", "/bin/false")
    with pytest.raises(mvw.InputError, match="the DICOM decoder failed on this file"):
        mvw.read(jpeg)
    monkeypatch.delenv("MVW_DECODER")
    assert np.array_equal(mvw.read(jpeg).array, expected)


def test_an_installed_module_finds_the_decoder_of_its_own_prefix(data, tmp_path):
    # The module installed into another prefix (<prefix>/lib/python3.11/dist-packages) runs the
    # helper of that prefix (<prefix>/lib/mvw/mvw-decoder) before this build tree's: here a
    # stand-in that leaves a mark and fails, so the read is the file's InputError.
    site = tmp_path / "prefix" / "lib" / "python3.11" / "dist-packages"
    site.mkdir(parents=True)
    shutil.copy(mvw.__file__, site)
    helper = tmp_path / "prefix" / "lib" / "mvw" / "mvw-decoder"
    helper.parent.mkdir()
    mark = tmp_path / "ran"
    helper.write_text(f"#!/bin/sh\ntouch '{mark}'\nexit 1\n")
    helper.chmod(0o755)
    jpeg = data / "pydicom" / "test_files" / "SC_rgb_jpeg_dcmtk.dcm"
    env = {k: v for k, v in os.environ.items() if k != "MVW_DECODER"}
    done = subprocess.run(
        [sys.executable, "-c", f"import mvw; assert mvw.__file__.startswith({str(site)!r}); "
                               f"mvw.read({str(jpeg)!r})"],
        env=dict(env, PYTHONPATH=str(site)), capture_output=True, text=True)
    assert "mvw.InputError" in done.stderr and "the DICOM decoder failed" in done.stderr, done.stderr
    assert mark.exists()
