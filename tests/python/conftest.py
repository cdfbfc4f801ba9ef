"""The pytest suite of the Python module `import mvw` (docs/python.md), run by CTest as `python`.

CTest sets PYTHONPATH to the build's python/ folder, MVW to the built `mvw` binary (the command
line each result is compared against) and MVW_DATA_DIR to the sample data (scripts/
fetch-sample-data): the tests fail, never skip, without them.
"""
import json
import os
import pathlib
import subprocess

import pytest


def _required(name):
    value = os.environ.get(name)
    if not value:
        raise RuntimeError(f"{name} is not set: run the suite through CTest (ctest -R ^python$)")
    return value


@pytest.fixture(scope="session")
def data():
    path = pathlib.Path(_required("MVW_DATA_DIR"))
    if not (path / "nipy").is_dir():
        raise RuntimeError(f"{path} holds no sample data: run scripts/fetch-sample-data")
    return path


@pytest.fixture(scope="session")
def mvw_cli():
    """Runs the `mvw` binary with the arguments given; returns its stdout as JSON."""
    binary = _required("MVW")

    def run(*args):
        done = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, f"mvw {' '.join(map(str, args))}: {done.stderr}"
        return json.loads(done.stdout)

    return run
