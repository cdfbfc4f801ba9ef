#!/usr/bin/python3
"""Independent geometry checks of mvw's DICOM reading (run by tests/real-data/dicom_geometry_test).

  slices VOLUME.nii OUT.json DIR SERIES  every acquired slice of series number SERIES in DIR
                                        (read with pydicom) against mvw's volume sampled
                                        trilinearly at that slice's pixel positions
  mosaic VOLUME.nii OUT.json FILE      a Siemens mosaic unpacked by nibabel.nicom against mvw's
                                        volume: world positions and voxel values

VOLUME is what mvw read, written by mvw's NIfTI writer (RAS affine in the sform). Needs
Debian's python3-numpy, python3-nibabel and python3-pydicom (/usr/bin/python3).
"""
import json
import sys
import warnings

import nibabel
import numpy as np
import pydicom

warnings.simplefilter("ignore")  # nibabel.nicom warns that it is experimental


def load_mvw(path):
    img = nibabel.load(path)
    data = np.asarray(img.dataobj, dtype=np.float64)
    if data.ndim > 3:
        data = data[..., 0]
    lps_from_ras = np.diag([-1.0, -1.0, 1.0, 1.0])
    world_from_index = lps_from_ras @ img.affine  # LPS mm, as DICOM
    return data, world_from_index


def trilinear(data, idx):
    """data sampled at continuous indices idx (N x 3); NaN where outside the volume."""
    shape = np.array(data.shape)
    # The NIfTI sform is float32: a grid point comes back up to ~1e-5 voxels off. Snap those.
    near = np.rint(idx)
    idx = np.where(np.abs(idx - near) < 1e-4, near, idx)
    out = np.full(len(idx), np.nan)
    inside = np.all((idx >= 0) & (idx <= shape - 1), axis=1)
    p = np.clip(idx[inside], 0, shape - 1)
    i0 = np.minimum(np.floor(p).astype(int), np.maximum(shape - 2, 0))
    f = p - i0
    acc = np.zeros(len(p))
    for corner in range(8):
        o = np.array([(corner >> a) & 1 for a in range(3)])
        w = np.prod(np.where(o, f, 1.0 - f), axis=1)
        j = np.minimum(i0 + o, shape - 1)
        v = data[j[:, 0], j[:, 1], j[:, 2]]
        acc += np.where(w > 0, w * v, 0.0)
    out[inside] = acc
    return out


def series_files(folder, number):
    import os
    files = []
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        try:
            d = pydicom.dcmread(path, stop_before_pixels=True)
        except Exception:
            continue
        if "PixelData" in d or hasattr(d, "Rows"):
            if number == "all" or int(getattr(d, "SeriesNumber", -1)) == int(number):
                files.append(path)
    return files


def slices(volume, out, files):
    data, world_from_index = load_mvw(volume)
    index_from_world = np.linalg.inv(world_from_index)
    rows = []
    for f in files:
        d = pydicom.dcmread(f)
        a = d.pixel_array.astype(np.float64) * float(getattr(d, "RescaleSlope", 1) or 1) + float(
            getattr(d, "RescaleIntercept", 0) or 0)
        iop = np.array(d.ImageOrientationPatient, dtype=float)
        ipp = np.array(d.ImagePositionPatient, dtype=float)
        dr, dc = (float(x) for x in d.PixelSpacing)  # between rows, between columns
        j, i = np.mgrid[0:a.shape[0], 0:a.shape[1]]
        world = ipp + np.outer(i.ravel() * dc, iop[:3]) + np.outer(j.ravel() * dr, iop[3:])
        idx = (index_from_world[:3, :3] @ world.T).T + index_from_world[:3, 3]
        sampled = trilinear(data, idx)
        ref = a.ravel()
        ok = ~np.isnan(sampled)
        diff = np.abs(sampled[ok] - ref[ok])
        sd = float(np.std(ref))
        rows.append({
            "file": f, "position": ipp.tolist(), "outside": int((~ok).sum()),
            "mean_abs_diff": float(diff.mean()) if diff.size else None,
            "max_abs_diff": float(diff.max()) if diff.size else None, "sd": sd,
            "ratio": float(diff.mean() / sd) if diff.size and sd > 0 else None})
    ratios = [r["ratio"] for r in rows if r["ratio"] is not None]
    summary = {"slices": len(rows), "outside": sum(r["outside"] for r in rows),
               "max_ratio": max(ratios), "mean_ratio": float(np.mean(ratios)),
               "max_abs_diff": max(r["max_abs_diff"] for r in rows if r["max_abs_diff"] is not None),
               "slices_outside": sum(1 for r in rows if r["mean_abs_diff"] is None),
               "per_slice": rows}
    json.dump(summary, open(out, "w"), indent=1)
    print(f"{len(rows)} slices: mean|diff|/SD max {summary['max_ratio']:.5f}, mean "
          f"{summary['mean_ratio']:.5f}; max |diff| {summary['max_abs_diff']:.4g}; "
          f"{summary['outside']} pixels outside the volume ({summary['slices_outside']} whole slices)")


def mosaic(volume, out, f):
    from nibabel.nicom import dicomwrappers
    w = dicomwrappers.wrapper_from_file(f)
    ref = np.asarray(w.get_data(), dtype=np.float64)  # (rows, columns, slices)
    affine = np.asarray(w.affine)  # LPS mm from (row index, column index, slice)
    data, world_from_index = load_mvw(volume)
    index_from_world = np.linalg.inv(world_from_index)
    r, c, s = np.mgrid[0:ref.shape[0], 0:ref.shape[1], 0:ref.shape[2]]
    ijk = np.stack([r.ravel(), c.ravel(), s.ravel(), np.ones(r.size)])
    world = affine @ ijk
    idx = index_from_world @ world
    nearest = np.rint(idx[:3])
    offset_mm = np.linalg.norm(world_from_index[:3, :3] @ (idx[:3] - nearest), axis=0)
    shape = np.array(data.shape)[:, None]
    inside = np.all((nearest >= 0) & (nearest < shape), axis=0)
    n = nearest[:, inside].astype(int)
    values = data[n[0], n[1], n[2]]
    diff = np.abs(values - ref.ravel()[inside])
    summary = {"reference_shape": list(ref.shape), "mvw_shape": list(data.shape),
               "max_position_error_mm": float(offset_mm.max()), "outside": int((~inside).sum()),
               "max_abs_diff": float(diff.max()), "reference_max": float(np.abs(ref).max()),
               "corner_lps": affine[:3, 3].tolist()}
    json.dump(summary, open(out, "w"), indent=1)
    print(json.dumps(summary))


if __name__ == "__main__":
    mode, volume, out, *files = sys.argv[1:]
    if mode == "slices":
        slices(volume, out, series_files(files[0], files[1]))
    else:
        mosaic(volume, out, files[0])
