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


@pytest.fixture(scope="session")
def releases_gil():
    """Runs `call` on a thread of its own while this thread wakes every millisecond, and fails
    unless this thread ran throughout: its longest wait between two wakings is under a quarter
    of the call's time. A call that holds the GIL keeps this thread asleep until it returns, its
    longest wait then the whole call. Returns the call's result, or raises its exception."""
    import threading
    import time

    def check(call, what):
        result, error = [], []

        def run():
            try:
                result.append(call())
            except BaseException as e:  # noqa: B036  reraised below, on the caller's thread
                error.append(e)

        thread = threading.Thread(target=run)
        start = time.perf_counter()
        thread.start()
        last, longest = start, 0.0
        while thread.is_alive():
            time.sleep(0.001)  # sleeps without the GIL, wakes only when it can take it again
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        took = time.perf_counter() - start
        assert took > 0.05, f"{what}: {took:.3f} s, too quick to tell whether it holds the GIL"
        assert longest < 0.25 * took, (f"{what} held the GIL: the other thread waited "
                                       f"{longest:.3f} s of its {took:.3f} s")
        if error:
            raise error[0]
        return result[0]

    return check
