"""docs/python.md's API reference is the docstrings of the module built now
(scripts/python-api-reference --check)."""
import pathlib
import subprocess
import sys


def test_api_reference_is_current():
    script = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "python-api-reference"
    done = subprocess.run([sys.executable, str(script), "--check"], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stdout + done.stderr
