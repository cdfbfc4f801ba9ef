"""The long calls (read, register, Study and its render; mvw.pacs.get and find in test_pacs.py)
release the GIL: the interpreter's other threads run while they work."""
import json
import time

import numpy as np

import mvw


def test_read_releases_the_gil(data, releases_gil):
    volume = releases_gil(lambda: mvw.read(data / "cranium" / "cranium.nii.gz"), "mvw.read")
    assert volume.shape == (256, 256, 108)


def test_register_releases_the_gil(data, releases_gil):
    fixed, moving = data / "nipy" / "anatomical.nii.gz", data / "nipy" / "functional.nii.gz"
    reg = releases_gil(lambda: mvw.register(fixed, moving), "mvw.register")
    assert np.allclose(reg.fixed_from_moving @ reg.moving_from_fixed, np.eye(4))


def test_study_and_render_release_the_gil(data, tmp_path, releases_gil):
    config = tmp_path / "study.json"
    config.write_text(json.dumps({
        "anatomical": {"path": str(data / "cranium" / "cranium.nii.gz")},
        "render": {"views": [{"name": "bone", "mode": "composite", "view": "anterior",
                              "preset": "ct-bone"}]}}))
    study = releases_gil(lambda: mvw.Study(config), "mvw.Study")
    # A render long enough to tell on this GL (llvmpipe or a GPU): about 0.3 s.
    start = time.perf_counter()
    study.render("bone", size=256)
    took = time.perf_counter() - start
    size = int(min(4096, 256 * (0.3 / max(took, 1e-4)) ** 0.5))
    image = releases_gil(lambda: study.render("bone", size=size), "mvw.Study.render")
    assert image.shape == (size, size, 4) and image[..., :3].std() > 0
