#!/usr/bin/python3
"""Checks of the DICOM objects mvw writes, by pydicom and numpy (independent of mvw's code).
usage: dicom_out_check.py sc FILE.dcm PNG...      the SC's frames equal the PNGs' RGB, in order
       dicom_out_check.py tags FILE.dcm KEY=VALUE  each DICOM keyword has the value given
       dicom_out_check.py clean FILE.dcm...        no private tag anywhere; every UID mvw made is
                                                   new (2.25. or the root in $MVW_UID_ROOT), valid
       dicom_out_check.py reg REG.dcm TFM [TYPE]   the moving item's matrix is the inverse of the
                                                   ITK transform's movingFromFixed, to 1e-6
       dicom_out_check.py series DIR NIFTI SERIES.nii.gz
                                                   the series (as mvw converted it to SERIES.nii.gz)
                                                   equals the resampled NIfTI within each slice's
                                                   rescale slope
       dicom_out_check.py topng FILE.dcm OUT.png   frame 0 (or every frame: OUT-NNN.png) to PNG
Exit 1 with one line per problem."""
import os
import re
import struct
import sys
import zlib

import numpy as np
import pydicom

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "view"))
import pngstat  # noqa: E402  (the PNG reader the viewer tests use, standard library only)


def read_png(path):
    """The PNG's RGB as an (h, w, 3) uint8 array, decoded by the viewer tests' reader."""
    w, h, bpp, rows = pngstat.read(path)
    return np.frombuffer(b"".join(rows), np.uint8).reshape(h, w, bpp)[:, :, :3]


def write_png(path, rgb):
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def frames(ds):
    a = ds.pixel_array
    return a[None] if int(getattr(ds, "NumberOfFrames", 1) or 1) == 1 else a


problems = []


def sc(path, pngs):
    ds = pydicom.dcmread(path)
    f = frames(ds)
    if ds.PhotometricInterpretation != "RGB" or ds.SamplesPerPixel != 3:
        problems.append(f"{path}: {ds.PhotometricInterpretation}, {ds.SamplesPerPixel} samples")
    if len(f) != len(pngs):
        problems.append(f"{path}: {len(f)} frames, {len(pngs)} PNGs")
        return
    for k, png in enumerate(pngs):
        ref = read_png(png)
        if f[k].shape != ref.shape:
            problems.append(f"{path}: frame {k} is {f[k].shape}, {png} {ref.shape}")
        elif not np.array_equal(f[k], ref):
            problems.append(f"{path}: frame {k} differs from {png} in "
                            f"{int((f[k] != ref).any(axis=2).sum())} pixels")


def tags(path, pairs):
    ds = pydicom.dcmread(path, stop_before_pixels=True)
    for pair in pairs:
        key, want = pair.split("=", 1)
        got = ds.get(key)
        got = "" if got is None else ("\\".join(str(v) for v in got)
                                      if isinstance(got, pydicom.multival.MultiValue) else str(got))
        if got != want:
            problems.append(f"{path}: {key} is '{got}', expected '{want}'")


UID = re.compile(r"^(0|[1-9][0-9]*)(\.(0|[1-9][0-9]*))*$")


def clean(paths):
    root = os.environ.get("MVW_UID_ROOT", "2.25")
    for path in paths:
        ds = pydicom.dcmread(path, stop_before_pixels=True)
        def walk(d):
            for e in d:
                if e.tag.is_private:
                    problems.append(f"{path}: private tag {e.tag}")
                if e.VR == "SQ":
                    for item in e.value:
                        walk(item)
                elif e.VR == "UI" and e.value:
                    for v in (e.value if isinstance(e.value, pydicom.multival.MultiValue) else [e.value]):
                        if len(v) > 64 or not UID.match(v):
                            problems.append(f"{path}: {e.keyword} '{v}' is not a valid UID")
        walk(ds)
        for key in ("SOPInstanceUID", "SeriesInstanceUID"):
            if not str(ds.get(key, "")).startswith(root + "."):
                problems.append(f"{path}: {key} {ds.get(key)} does not start with {root}.")
        if ds.file_meta.MediaStorageSOPInstanceUID != ds.SOPInstanceUID:
            problems.append(f"{path}: the meta header's SOP instance differs")


def itk_moving_from_fixed(tfm):
    params = fixed = None
    for line in open(tfm):
        if line.startswith("Parameters:"):
            params = [float(v) for v in line.split(":")[1].split()]
        elif line.startswith("FixedParameters:"):
            fixed = [float(v) for v in line.split(":")[1].split()]
    a = np.array(params[:9]).reshape(3, 3)
    t = np.array(params[9:12])
    c = np.array(fixed[:3])
    m = np.eye(4)
    m[:3, :3] = a
    m[:3, 3] = a @ -c + c + t
    return m


def reg(path, tfm, kind=None):
    ds = pydicom.dcmread(path)
    if ds.Modality != "REG" or ds.SOPClassUID != "1.2.840.10008.5.1.4.1.1.66.1":
        problems.append(f"{path}: not a Spatial Registration ({ds.Modality}, {ds.SOPClassUID})")
    items = ds.RegistrationSequence
    moving = items[-1].MatrixRegistrationSequence[0].MatrixSequence[0]
    m = np.array([float(v) for v in moving.FrameOfReferenceTransformationMatrix]).reshape(4, 4)
    want = np.linalg.inv(itk_moving_from_fixed(tfm))
    err = np.abs(m - want).max()
    print(f"REG matrix against the .tfm's inverse: max abs difference {err:.2e}")
    if err > 1e-6:
        problems.append(f"{path}: matrix differs from the inverse of {tfm} by {err:g}")
    if kind and moving.FrameOfReferenceTransformationMatrixType != kind:
        problems.append(f"{path}: matrix type {moving.FrameOfReferenceTransformationMatrixType}, "
                        f"expected {kind}")
    if len(items) == 2 and items[0].FrameOfReferenceUID != ds.FrameOfReferenceUID:
        problems.append(f"{path}: the first registration item is not the REG's own frame")


def series(folder, nifti, converted):
    import nibabel
    files = sorted(os.path.join(folder, f) for f in os.listdir(folder))
    slopes, stored = [], 0.0
    for f in files:
        d = pydicom.dcmread(f)
        slopes.append(float(d.RescaleSlope))
        stored = max(stored, float(np.abs(d.pixel_array).max()) * slopes[-1])
    a, b = nibabel.load(nifti), nibabel.load(converted)
    if not np.allclose(a.affine, b.affine, atol=1e-3):
        problems.append(f"{converted}: affine\n{b.affine}\n differs from {nifti}'s\n{a.affine}")
    x, y = a.get_fdata(), b.get_fdata()
    if x.shape != y.shape:
        problems.append(f"{converted}: shape {y.shape}, {nifti} {x.shape}")
        return
    x = np.nan_to_num(x)
    d = np.abs(x - y)
    # Each slice is stored with its own slope: the error is at most half of it, in the unit
    # read back (mvw's factor from the stored unit, e.g. Bq/ml -> SUVbw, is the ratio of the
    # largest values read and stored).
    factor = np.abs(y).max() / stored if stored > 0 else 1.0
    tol = 0.5 * max(slopes) * factor * 1.0001 + 1e-6 * np.abs(x).max()
    print(f"series against the NIfTI: max abs difference {d.max():.3g} (tolerance {tol:.3g}), "
          f"{len(files)} files")
    if d.max() > tol:
        problems.append(f"{converted}: differs from {nifti} by up to {d.max():g} (> {tol:g})")


def topng(path, out):
    ds = pydicom.dcmread(path)
    f = frames(ds)
    if len(f) == 1:
        write_png(out, f[0])
    else:
        base = out[:-4]
        for k in range(len(f)):
            write_png(f"{base}-{k:03d}.png", f[k])


def main():
    cmd, args = sys.argv[1], sys.argv[2:]
    {"sc": lambda: sc(args[0], args[1:]), "tags": lambda: tags(args[0], args[1:]),
     "clean": lambda: clean(args), "reg": lambda: reg(*args),
     "series": lambda: series(*args), "topng": lambda: topng(*args)}[cmd]()
    for p in problems:
        print("  " + p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
