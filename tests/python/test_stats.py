"""mvw.stats against `mvw stats --json` on the same volume and ROI: the same fields, the same
numbers."""
import numpy as np
import pytest

import mvw


def test_sphere_equals_cli(data, mvw_cli):
    path = data / "derived" / "pet_like.nii.gz"
    volume = mvw.read(path)
    centre = volume.affine_lps @ np.array([*(n // 2 for n in volume.shape[:3]), 1.0])
    sphere = (*centre[:3], 15.0)
    got = mvw.stats(volume, sphere=sphere)
    cli = mvw_cli("stats", path, "--json", "--sphere", *map(repr, sphere))
    assert isinstance(got, dict)
    assert got == cli[0]
    assert got["voxels"] > 0


def test_box_with_threshold_fraction_equals_cli(data, mvw_cli):
    path = data / "nipy" / "anatomical.nii.gz"
    volume = mvw.read(path)
    lo = volume.affine_lps @ np.array([10, 10, 10, 1.0])
    hi = volume.affine_lps @ np.array([40, 50, 30, 1.0])
    box = (*np.minimum(lo, hi)[:3], *np.maximum(lo, hi)[:3])  # corners in LPS order
    got = mvw.stats(volume, box=box, threshold_fraction=0.41)
    cli = mvw_cli("stats", path, "--json", "--box", *map(repr, box), "--threshold-fraction",
                  "0.41")
    assert got == cli[0]
    assert got["metabolic_voxels"] > 0


def test_labels_equal_cli(data, mvw_cli):
    labels = data / "mricron" / "aal.nii.gz"
    volume = mvw.read(labels)
    every = mvw.stats(volume, labels=labels)
    assert isinstance(every, list) and len(every) > 100
    assert every == mvw_cli("stats", labels, "--json", "--labels", labels)
    one = mvw.stats(volume, labels=labels, label=1)
    assert one == mvw_cli("stats", labels, "--json", "--labels", labels, "--label", "1")[0]


def test_roi_choice_is_checked(data):
    volume = mvw.read(data / "derived" / "pet_like.nii.gz")
    with pytest.raises(ValueError, match="exactly one of sphere, box or labels"):
        mvw.stats(volume)
    with pytest.raises(ValueError, match="exactly one"):
        mvw.stats(volume, sphere=(0, 0, 0, 5), box=(0, 0, 0, 1, 1, 1))
    with pytest.raises(ValueError, match="4 numbers"):
        mvw.stats(volume, sphere=(0, 0, 5))
    with pytest.raises(ValueError, match="threshold_fraction"):
        mvw.stats(volume, sphere=(0, 0, 0, 5), threshold_fraction=1.5)
    with pytest.raises(ValueError, match="^mvw.stats: label needs labels$"):
        mvw.stats(volume, sphere=(0, 0, 0, 5), label=2)
