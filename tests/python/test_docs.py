"""docs/python.md: its API reference is the docstrings of the module built now
(scripts/python-api-reference --check), and its worked example runs as it stands."""
import importlib.util
import os
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_api_reference_is_current():
    script = ROOT / "scripts" / "python-api-reference"
    done = subprocess.run([sys.executable, str(script), "--check"], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def test_worked_example_runs(data, tmp_path):
    """The page's first Python block, run from a folder whose data/ is the sample data (as the
    repository root's), writing into a temporary folder under TMPDIR: the transform, the PET on
    the CT's grid, and the figure exactly where matplotlib is installed."""
    text = (ROOT / "docs" / "python.md").read_text()
    section = text[text.index("## A worked example"):text.index("## API\n")]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    work = tmp_path / "root"
    work.mkdir()
    (work / "data").symlink_to(data)
    (tmp_path / "tmp").mkdir()
    done = subprocess.run([sys.executable, "-c", code], cwd=work, capture_output=True, text=True,
                          env=dict(os.environ, TMPDIR=str(tmp_path / "tmp")))
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("<mvw.Volume 256 x 256 x 108 int16 CT in HU"), lines
    assert lines[2].startswith("4.031") and " 4.928" in lines[2], lines  # the comments' figures
    out = pathlib.Path(lines[-1].removeprefix("written into "))
    assert out.parent == tmp_path / "tmp"
    assert (out / "pet_to_ct.tfm").read_text().startswith("#Insight Transform File")
    assert (out / "pet_on_ct.nii.gz").stat().st_size > 0
    figure = out / "pet-ct.png"
    if importlib.util.find_spec("matplotlib"):
        assert mvw_png_shape(figure) == (440, 900, 4)
    else:
        assert not figure.exists()


def mvw_png_shape(path):
    import mvw
    return mvw.read_png(path).shape
