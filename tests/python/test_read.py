"""mvw.read and mvw.Volume against independent readers: nibabel for NIfTI, pydicom for DICOM."""
import gc

import nibabel
import numpy as np
import pydicom
import pytest

import mvw


def assert_same_voxels_in_world(volume, expected, affine_ras):
    """Every voxel of `expected` (placed by `affine_ras`, nibabel's) has the same value at the
    same world position in `volume`. mvw may store the axes in another order (a NIfTI with
    qfac -1 has its slices reversed into a right-handed index frame, said in the notes), so the
    two are matched through their affines: each index of one lands on a whole index of the
    other."""
    mvw_from_expected = np.linalg.inv(volume.affine_ras) @ affine_ras
    rotation = mvw_from_expected[:3, :3]
    np.testing.assert_allclose(rotation, np.round(rotation), atol=1e-6)
    assert sorted(np.abs(np.round(rotation)).sum(axis=0)) == [1, 1, 1]  # a signed permutation
    ijk = np.indices(expected.shape[:3]).reshape(3, -1)
    mapped = mvw_from_expected[:3, :3] @ ijk + mvw_from_expected[:3, 3:]
    np.testing.assert_allclose(mapped, np.round(mapped), atol=1e-4)
    i, j, k = np.round(mapped).astype(int)
    got = volume.array[i, j, k]
    np.testing.assert_array_equal(got, expected.reshape(-1, *expected.shape[3:]))


def test_nifti_equals_nibabel(data):
    for name in ["nipy/anatomical.nii.gz", "nibabel/anatomical.nii", "mricron/aal.nii.gz"]:
        path = data / name
        volume = mvw.read(path)
        image = nibabel.load(path)
        expected = np.asanyarray(image.dataobj)  # nibabel applies scl_slope / scl_inter
        assert volume.array.shape == expected.shape, name
        assert_same_voxels_in_world(volume, expected, image.affine)
        np.testing.assert_allclose(sorted(volume.spacing), sorted(image.header.get_zooms()[:3]),
                                   rtol=1e-6)
        assert volume.format.startswith("NIfTI")


def test_affines_are_lps_and_ras_of_one_geometry(data):
    volume = mvw.read(data / "nipy" / "anatomical.nii.gz")
    np.testing.assert_array_equal(np.diag([-1, -1, 1, 1]) @ volume.affine_lps, volume.affine_ras)
    assert volume.affine_lps.shape == (4, 4)
    np.testing.assert_array_equal(volume.affine_lps[3], [0, 0, 0, 1])


def test_dicom_equals_pydicom(data):
    folder = data / "cranium" / "dicom"
    volume = mvw.read(folder)
    assert volume.modality == "CT" and volume.unit == "HU"
    slices = [pydicom.dcmread(f) for f in sorted(folder.iterdir())]
    assert volume.shape == (slices[0].Columns, slices[0].Rows, len(slices))
    lps = volume.affine_lps
    row, col = np.array(slices[0].ImageOrientationPatient[:3]), np.array(
        slices[0].ImageOrientationPatient[3:])
    dy, dx = map(float, slices[0].PixelSpacing)  # row spacing, column spacing
    np.testing.assert_allclose(lps[:3, 0], row * dx, atol=1e-6)
    np.testing.assert_allclose(lps[:3, 1], col * dy, atol=1e-6)
    index_from_world = np.linalg.inv(lps)
    seen = set()
    for s in slices:
        # The slice's k from its position: mvw's geometry must put it on a whole slice.
        ijk = index_from_world @ np.append(np.array(s.ImagePositionPatient, float), 1.0)
        np.testing.assert_allclose(ijk[:2], [0, 0], atol=1e-4)
        k = int(round(ijk[2]))
        assert abs(ijk[2] - k) < 1e-4
        seen.add(k)
        hu = s.pixel_array.T * float(s.RescaleSlope) + float(s.RescaleIntercept)
        np.testing.assert_array_equal(volume.array[:, :, k], hu)
    assert seen == set(range(len(slices)))


def test_frames_of_a_4d_volume(data):
    path = data / "nibabel" / "example4d.nii.gz"
    every = mvw.read(path)
    image = nibabel.load(path)
    assert every.shape == image.shape
    assert_same_voxels_in_world(every, np.asanyarray(image.dataobj), image.affine)
    one = mvw.read(path, frame=1)
    assert one.shape == image.shape[:3]
    np.testing.assert_array_equal(one.array, every.array[..., 1])
    mean = mvw.read(path, frame="mean")
    np.testing.assert_allclose(mean.array, every.array.mean(axis=3), rtol=1e-5, atol=1e-3)


def test_array_is_a_view_that_keeps_the_volume_alive(data):
    volume = mvw.read(data / "nipy" / "functional.nii.gz", frame=0)
    a, b = volume.array, volume.array
    assert np.shares_memory(a, b)  # no copy: two views of the same voxels
    assert not a.flags.owndata
    a[0, 0, 0] = 12345
    assert b[0, 0, 0] == 12345
    view = mvw.read(data / "nipy" / "anatomical.nii.gz").array  # the Volume goes at once
    expected = np.array(mvw.read(data / "nipy" / "anatomical.nii.gz").array)  # a copy
    gc.collect()
    mvw.read(data / "nipy" / "functional.nii.gz")  # would reuse freed memory
    np.testing.assert_array_equal(view, expected)


def test_from_array_and_to_nibabel():
    values = np.arange(2 * 3 * 4, dtype=np.int16).reshape(2, 3, 4)
    affine = np.array([[2.0, 0, 0, -10], [0, 3, 0, 20], [0, 0, 4, 30], [0, 0, 0, 1]])
    volume = mvw.Volume.from_array(values, affine_ras=affine, modality="CT", unit="HU")
    np.testing.assert_array_equal(volume.array, values)
    np.testing.assert_array_equal(volume.affine_ras, affine)
    assert volume.spacing == (2.0, 3.0, 4.0) and volume.unit == "HU"
    assert volume.array.dtype == np.int16
    image = volume.to_nibabel()
    np.testing.assert_array_equal(np.asanyarray(image.dataobj), values)
    np.testing.assert_array_equal(image.affine, affine)
    lps = mvw.Volume.from_array(values.astype(np.float32), affine_lps=volume.affine_lps)
    np.testing.assert_array_equal(lps.affine_ras, affine)


def test_suv_and_notes_and_repr(data):
    pet = mvw.read(data / "derived" / "pet_like.nii.gz")
    assert pet.suv is None  # NIfTI carries no DICOM dose tags
    assert isinstance(pet.notes, list)
    assert "mvw.Volume" in repr(pet)


def test_study_config_volumes(data, tmp_path):
    config = tmp_path / "study.json"
    config.write_text('{ "anatomical": { "path": "%s" }, "functional": { "path": "%s" } }'
                      % (data / "nipy" / "anatomical.nii.gz", data / "nipy" / "functional.nii.gz"))
    anatomical = mvw.read(config)
    np.testing.assert_array_equal(anatomical.array,
                                  mvw.read(data / "nipy" / "anatomical.nii.gz").array)
    functional = mvw.read(config, volume="functional")
    assert functional.shape[:3] == mvw.read(data / "nipy" / "functional.nii.gz").shape[:3]
    with pytest.raises(ValueError, match="names its series itself"):
        mvw.read(config, series="1")
