#!/usr/bin/python3
"""Synthetic DICOM SEG files (pydicom) for the SEG reader: good ones with known masks and bad
ones that lie. Writes into OUTDIR: ok-*.dcm (must load) and bad-*.dcm (must be refused), and
expected.json with each good file's segment voxel counts.

usage: seg_synthetic.py OUTDIR
"""
import json
import os
import sys

import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.sequence import Sequence
from pydicom.uid import ExplicitVRLittleEndian, generate_uid

SEG_CLASS = "1.2.840.10008.5.1.4.1.1.66.4"
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
rng = np.random.default_rng(7)
ROWS, COLS = 7, 5  # 35 pixels a frame: 1-bit frames do not start on byte boundaries


def item(**kw):
    d = Dataset()
    for k, v in kw.items():
        setattr(d, k, v)
    return d


def make(frames, kind="BINARY", nframes=None, segments=(1, 2), pixel_bytes=None, spacing=2.5):
    """frames: list of (segment number, z position, in-plane shift (x, y), mask rows x cols)."""
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = SEG_CLASS
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = Dataset()
    ds.file_meta = meta
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.SOPClassUID, ds.SOPInstanceUID = SEG_CLASS, meta.MediaStorageSOPInstanceUID
    ds.Modality = "SEG"
    ds.SeriesInstanceUID, ds.StudyInstanceUID = generate_uid(), generate_uid()
    ds.FrameOfReferenceUID = "1.2.826.0.1.3680043.8.498.1"
    ds.SeriesNumber, ds.SeriesDescription = 3, "synthetic segmentation"
    ds.Rows, ds.Columns = ROWS, COLS
    ds.NumberOfFrames = len(frames) if nframes is None else nframes
    ds.SamplesPerPixel, ds.PhotometricInterpretation, ds.PixelRepresentation = 1, "MONOCHROME2", 0
    ds.SegmentationType = kind
    if kind == "BINARY":
        ds.BitsAllocated, ds.BitsStored, ds.HighBit = 1, 1, 0
    else:
        ds.BitsAllocated, ds.BitsStored, ds.HighBit = 8, 8, 7
        ds.SegmentationFractionalType, ds.MaximumFractionalValue = "PROBABILITY", 200
    ds.SegmentSequence = Sequence([
        item(SegmentNumber=n, SegmentLabel="segment %d" % n, SegmentAlgorithmType="MANUAL",
             RecommendedDisplayCIELabValue=[65535, 32896, 32896]) for n in segments])
    ds.SharedFunctionalGroupsSequence = Sequence([item(
        PlaneOrientationSequence=Sequence([item(ImageOrientationPatient=[1, 0, 0, 0, 1, 0])]),
        PixelMeasuresSequence=Sequence([item(PixelSpacing=[1.5, 2.0], SliceThickness=spacing,
                                             SpacingBetweenSlices=spacing)]))])
    groups = []
    for number, z, (sx, sy), _ in frames:
        groups.append(item(
            SegmentIdentificationSequence=Sequence([item(ReferencedSegmentNumber=number)]),
            PlanePositionSequence=Sequence([item(ImagePositionPatient=[-10 + sx, 20 + sy, z])])))
    ds.PerFrameFunctionalGroupsSequence = Sequence(groups)
    stack = np.stack([m for *_, m in frames]).astype(np.uint8)
    if kind == "BINARY":
        data = np.packbits(stack.ravel() != 0, bitorder="little").tobytes()
    else:
        data = stack.ravel().tobytes()
    if pixel_bytes is not None:
        data = data[:pixel_bytes]
    if len(data) % 2:
        data += b"\0"
    ds.PixelData = data
    ds["PixelData"].VR = "OB"
    return ds


def mask(p=0.5):
    return (rng.random((ROWS, COLS)) < p).astype(np.uint8)


expected = {}
# Segment 1 on slices 0 and 2 (a gap at 1), segment 2 on slice 0 overlapping segment 1, and
# written out of order.
m1a, m1b, m2 = mask(), mask(), mask()
frames = [(1, 5.0, (0, 0), m1b), (1, 0.0, (0, 0), m1a), (2, 0.0, (0, 0), m2)]
make(frames).save_as(os.path.join(out, "ok-binary-gap-overlap.dcm"), write_like_original=False)
expected["ok-binary-gap-overlap.dcm"] = {
    "dims": [COLS, ROWS, 3], "counts": {"1": int(m1a.sum() + m1b.sum()), "2": int(m2.sum())},
    "overlap": int((m1a & m2).sum())}
# FRACTIONAL: a voxel belongs from half the maximum fractional value (200) up.
f1 = rng.integers(0, 201, (ROWS, COLS)).astype(np.uint8)
make([(1, 0.0, (0, 0), f1)], kind="FRACTIONAL", segments=(1,)).save_as(
    os.path.join(out, "ok-fractional.dcm"), write_like_original=False)
expected["ok-fractional.dcm"] = {"dims": [COLS, ROWS, 1], "counts": {"1": int((f1 >= 100).sum())},
                                  "overlap": 0}

bad = {
    "bad-truncated-pixels.dcm": make(frames, pixel_bytes=5),
    "bad-frames-lie.dcm": make(frames, nframes=1000),
    "bad-unknown-segment.dcm": make([(9, 0.0, (0, 0), m1a)]),
    "bad-inplane-shift.dcm": make([(1, 0.0, (0, 0), m1a), (1, 2.5, (3, 0), m1b)]),
    "bad-between-slices.dcm": make([(1, 0.0, (0, 0), m1a), (1, 1.25, (0, 0), m1b)]),
    "bad-span-huge.dcm": make([(1, 0.0, (0, 0), m1a), (1, 1e9, (0, 0), m1b)]),
    "bad-fractional-1bit.dcm": make(frames),
}
bad["bad-fractional-1bit.dcm"].SegmentationType = "FRACTIONAL"
for name, ds in bad.items():
    ds.save_as(os.path.join(out, name), write_like_original=False)
json.dump(expected, open(os.path.join(out, "expected.json"), "w"), indent=1)

# A folder of one PET series and a SEG of it (the SEG opens as the series' segmentation, with no
# --series): 4 slices on the SEG's grid, values from a slope; the segments' metabolic volumes,
# their means, TLG and the total over both segments (the union, each at its own threshold),
# computed here with numpy for the test to compare with `mvw stats`.
PET_CLASS = "1.2.840.10008.5.1.4.1.1.128"
folder = os.path.join(out, "pet-with-seg")
os.makedirs(folder, exist_ok=True)
study_uid, series_uid = generate_uid(), generate_uid()
slope = 0.01
stored = rng.integers(0, 1000, (4, ROWS, COLS)).astype(np.uint16)
for k in range(4):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = PET_CLASS
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = Dataset()
    ds.file_meta = meta
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.SOPClassUID, ds.SOPInstanceUID = PET_CLASS, meta.MediaStorageSOPInstanceUID
    ds.Modality, ds.Units = "PT", "GML"
    ds.PatientID, ds.PatientName = "synthetic", "synthetic"
    ds.StudyInstanceUID, ds.SeriesInstanceUID = study_uid, series_uid
    ds.FrameOfReferenceUID = "1.2.826.0.1.3680043.8.498.1"
    ds.SeriesNumber, ds.SeriesDescription, ds.InstanceNumber = 2, "synthetic PET", k + 1
    ds.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
    ds.ImagePositionPatient = [-10, 20, 2.5 * k]
    ds.PixelSpacing, ds.SliceThickness = [1.5, 2.0], 2.5
    ds.Rows, ds.Columns = ROWS, COLS
    ds.SamplesPerPixel, ds.PhotometricInterpretation, ds.PixelRepresentation = 1, "MONOCHROME2", 0
    ds.BitsAllocated, ds.BitsStored, ds.HighBit = 16, 16, 15
    ds.RescaleSlope, ds.RescaleIntercept = slope, 0
    ds.PixelData = stored[k].tobytes()
    ds.save_as(os.path.join(folder, "pet-%d.dcm" % k), write_like_original=False)
s1 = [mask(0.6) for _ in range(2)]
s2 = mask(0.6)
pet_seg = make([(1, 0.0, (0, 0), s1[0]), (1, 2.5, (0, 0), s1[1]), (2, 2.5, (0, 0), s2)])
pet_seg.StudyInstanceUID = study_uid
pet_seg.save_as(os.path.join(folder, "seg.dcm"), write_like_original=False)
values = stored.astype(np.float64) * slope  # [k, row, column]
seg_masks = {1: np.zeros(values.shape, bool), 2: np.zeros(values.shape, bool)}
seg_masks[1][0], seg_masks[1][1], seg_masks[2][1] = s1[0] != 0, s1[1] != 0, s2 != 0
voxel_ml = 1.5 * 2.0 * 2.5 / 1000.0
FRACTION = 0.5
pet_expected = {"fraction": FRACTION, "segments": {}}
union = np.zeros(values.shape, bool)
for number, m in seg_masks.items():
    t = FRACTION * values[m].max()
    hot = m & (values >= t)
    union |= hot
    pet_expected["segments"][str(number)] = {
        "voxels": int(m.sum()), "metabolic_voxels": int(hot.sum()),
        "metabolic_volume_ml": float(hot.sum() * voxel_ml),
        "metabolic_mean": float(values[hot].mean()), "tlg": float(values[hot].sum() * voxel_ml)}
pet_expected["total"] = {
    "voxels": int((seg_masks[1] | seg_masks[2]).sum()), "metabolic_voxels": int(union.sum()),
    "metabolic_volume_ml": float(union.sum() * voxel_ml),
    "metabolic_mean": float(values[union].mean()), "tlg": float(values[union].sum() * voxel_ml),
    "overlap": int((seg_masks[1] & seg_masks[2]).sum())}
json.dump(pet_expected, open(os.path.join(out, "pet-with-seg.json"), "w"), indent=1)
print("wrote %d files to %s" % (len(expected) + len(bad), out))
