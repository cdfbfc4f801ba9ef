"""mvw.Study.render against `mvw render`'s PNGs: the same pixels, byte for byte, for the config's
views as named, a size given (--size) and a view given as a dict; and renders from several
Python threads at once."""
import json
import os
import subprocess
import threading

import numpy as np
import pytest

import mvw

# Small renders of the Cranium CT (NIfTI: the quickest read): an annotated composite, a depth-cued
# MIP with its colour bar and a windowed MPR, so every painter path is compared.
VIEWS = [
    {"name": "bone", "mode": "composite", "view": "anterior", "preset": "ct-bone", "width": 96,
     "height": 80},
    {"name": "mip", "mode": "mip", "view": "left", "window": 2000, "level": 900, "width": 72,
     "height": 72, "depth_cue": {"brightness": 0.0, "amount": 0.8, "contrast": 0.35}},
    {"name": "axial", "mode": "mpr", "view": "axial", "window": 400, "level": 40, "width": 64,
     "height": 64, "plane_offset_mm": 20},
]


@pytest.fixture(scope="module")
def config(data, tmp_path_factory):
    folder = tmp_path_factory.mktemp("render")
    path = folder / "study.json"
    path.write_text(json.dumps({"anatomical": {"path": str(data / "cranium" / "cranium.nii.gz")},
                                "render": {"views": VIEWS}}))
    return path


def cli_render(config, out, *args):
    done = subprocess.run([os.environ["MVW"], "render", str(config), "-o", str(out), *args],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return out


@pytest.fixture(scope="module")
def study(config):
    return mvw.Study(config)


def test_views_equal_cli_pngs(study, config, tmp_path):
    out = cli_render(config, tmp_path / "out")
    assert study.views == [v["name"] for v in VIEWS]
    assert study.gl_backend == json.loads((out / "render.json").read_text())["gl_backend"]
    for view in VIEWS:
        got = study.render(view["name"])
        assert got.dtype == np.uint8 and got.shape == (view["height"], view["width"], 4)
        png = mvw.read_png(out / (view["name"] + ".png"))
        assert np.array_equal(got, png), view["name"]
        assert got[..., :3].std() > 0  # not a blank image
        assert (got[..., 3] == 255).all()  # opaque: composited over the background
    assert np.array_equal(study.render(), study.render(VIEWS[0]["name"]))  # None: the first


def test_size_and_dict_view_equal_cli(study, config, tmp_path):
    # A view of the caller's own, as a dict: as the config holding it renders it; with a size,
    # as --size renders both it and a view of the config.
    own = {"name": "skin", "mode": "composite", "view": "left", "azimuth": -35, "preset": "ct-skin",
           "width": 56, "height": 56}
    other = tmp_path / "own.json"
    other.write_text(json.dumps({"anatomical": json.loads(config.read_text())["anatomical"],
                                 "render": {"views": VIEWS + [own]}}))
    out = cli_render(other, tmp_path / "own", "--only-view", "skin", "--only-view", "mip",
                     "--size", "48")
    assert np.array_equal(study.render("mip", size=48), mvw.read_png(out / "mip.png"))
    skin = study.render(own, size=48)
    assert skin.shape == (48, 48, 4) and np.array_equal(skin, mvw.read_png(out / "skin.png"))
    assert study.render(own).shape == (56, 56, 4)  # the view's own size without one


def test_study_from_dict_and_threads(study, config):
    from_dict = mvw.Study(json.loads(config.read_text()))
    expected = study.render("axial")
    results = [None] * 4

    def render(k):
        results[k] = (from_dict if k % 2 else study).render("axial")

    threads = [threading.Thread(target=render, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r, expected)


def test_render_errors(study, data, tmp_path):
    with pytest.raises(ValueError, match="no view 'nope'.*bone, mip, axial"):
        study.render("nope")
    with pytest.raises(TypeError, match="view is a view's name"):
        study.render(3)
    with pytest.raises(ValueError, match="size is 1 to 8192"):
        study.render(size=0)
    with pytest.raises(mvw.InputError, match="mode"):
        study.render({"name": "bad", "mode": "nope"})
    with pytest.raises(mvw.InputError, match="missing.json"):
        mvw.Study(tmp_path / "missing.json")
    with pytest.raises(TypeError):
        mvw.Study(42)
    with pytest.raises(mvw.InputError, match="nothing.nii"):
        mvw.Study({"anatomical": {"path": str(tmp_path / "nothing.nii")}})


def test_one_backend_at_a_time(study, config):
    """The GL functions are loaded for one backend at a time (OSMesa and EGL are separate
    libraries): a Study on another backend while one lives is refused, saying so (the same
    backend is accepted: test_study_from_dict_and_threads)."""
    backend = study.gl_backend
    other = "egl" if backend == "osmesa" else "osmesa"
    with pytest.raises(ValueError, match=f"renders with {backend} .* would use"):
        mvw.Study(config, gl=other)
    assert study.render("axial").shape == (64, 64, 4)  # the refusal left the others whole


def test_a_study_deleted_leaves_the_others_whole(study, config):
    """A Study's GL objects go with its own context: deleting one (its names are the same
    numbers as another context's) leaves another Study's textures alone."""
    other = mvw.Study(config)
    expected = [other.render(v["name"]) for v in VIEWS]
    study.render("bone")  # `study` is current on the GL thread when `other` goes
    del other
    for view, image in zip(VIEWS, expected):
        assert np.array_equal(study.render(view["name"]), image)
