"""mvw.register against `mvw register`: the same matrices, the same report, the same resampled
volume and transform file."""
import json
import os
import subprocess

import numpy as np
import pytest

import mvw


@pytest.fixture(scope="module")
def pair(data, tmp_path_factory):
    """The nipy T1 / fMRI pair: mvw register's matrices and outputs, and the volumes."""
    fixed, moving = data / "nipy" / "anatomical.nii.gz", data / "nipy" / "functional.nii.gz"
    out = tmp_path_factory.mktemp("register") / "out"
    done = subprocess.run([os.environ["MVW"], "register", "--fixed", str(fixed), "--moving",
                           str(moving), "-o", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return fixed, moving, out


def test_matrices_and_report_equal_cli(pair, tmp_path):
    fixed, moving, out = pair
    reg = mvw.register(fixed, moving)
    cli = json.loads((out / "registration.json").read_text())
    assert np.array_equal(reg.fixed_from_moving, np.array(cli["fixed_from_moving"]))
    assert np.array_equal(reg.moving_from_fixed, np.array(cli["moving_from_fixed"]))
    report = reg.report
    for key in ("fixed", "moving", "outputs", "seconds"):
        report.pop(key), cli.pop(key)
    for level in report["levels"] + cli["levels"]:
        level.pop("seconds")
    assert report == cli
    # RAS: the same map with x and y negated on both sides.
    flip = np.diag([-1.0, -1.0, 1.0, 1.0])
    assert np.allclose(reg.fixed_from_moving_ras, flip @ reg.fixed_from_moving @ flip)
    assert np.allclose(reg.fixed_from_moving @ reg.moving_from_fixed, np.eye(4))
    # The transform file, byte for byte; the resampled volume, voxel for voxel.
    reg.write_tfm(tmp_path / "t.tfm")
    assert (tmp_path / "t.tfm").read_bytes() == (out / "transform.tfm").read_bytes()
    resampled = reg.resample()
    written = mvw.read(out / "functional_on_anatomical.nii.gz")
    ref = mvw.read(fixed)
    assert resampled.shape[:3] == ref.shape
    assert np.array_equal(resampled.affine_lps, ref.affine_lps)
    assert np.array_equal(resampled.array, written.array)


def test_volumes_in_affine_and_errors(pair):
    fixed, moving, _ = pair
    a = mvw.read(fixed)
    with pytest.raises(ValueError, match="method is 'rigid' or 'affine'"):
        mvw.register(a, a, method="bspline")
    with pytest.raises(ValueError, match="initialisation"):
        mvw.register(a, a, initialisation="nope")
    with pytest.raises(TypeError, match="fixed must be an mvw.Volume or a path"):
        mvw.register(42, a)
    with pytest.raises(mvw.InputError, match="missing.nii"):
        mvw.register(a, fixed.parent / "missing.nii")
