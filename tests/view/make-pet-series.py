#!/usr/bin/python3
# A PT series in the study of a CT series, for the viewer's PACS test: the PET-like phantom
# (a NIfTI made from the sample CT, so it lies in the CT's frame of reference) written as PET
# Image Storage files, one per slice, with the CT's patient, study and frame of reference, so
# the PACS holds a PET/CT study of two series as a scanner would send it. Values in Bq/ml
# (Units BQML, 16-bit with a rescale slope); no dose information (no SUV).
# usage: make-pet-series.py NIFTI CT_DIR OUT_DIR
import os
import sys

import nibabel
import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileDataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, generate_uid

nifti, ct_dir, out = sys.argv[1:4]
ct = pydicom.dcmread(os.path.join(ct_dir, sorted(os.listdir(ct_dir))[0]), stop_before_pixels=True)
image = nibabel.load(nifti)
data = np.asarray(image.get_fdata(), dtype=np.float64)  # i, j, k in the NIfTI's RAS frame
affine = image.affine
# LPS = diag(-1, -1, 1) RAS: the index axes' directions and the first voxel's position in LPS.
lps = np.diag([-1.0, -1.0, 1.0]) @ affine[:3, :3]
origin = np.diag([-1.0, -1.0, 1.0]) @ affine[:3, 3]
spacing = np.linalg.norm(lps, axis=0)
row_dir, col_dir = lps[:, 0] / spacing[0], lps[:, 1] / spacing[1]
slope = max(float(data.max()), 1e-6) / 32000.0
series_uid = generate_uid()
os.makedirs(out, exist_ok=True)
for k in range(data.shape[2]):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.128"  # PET Image Storage
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = FileDataset(None, {}, file_meta=meta, preamble=b"\0" * 128)
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    for key in ("PatientName", "PatientID", "PatientBirthDate", "PatientSex", "StudyInstanceUID",
                "StudyDate", "StudyTime", "StudyID", "AccessionNumber", "ReferringPhysicianName",
                "FrameOfReferenceUID", "StudyDescription"):
        setattr(ds, key, getattr(ct, key, ""))
    ds.Modality = "PT"
    ds.SeriesInstanceUID = series_uid
    ds.SeriesNumber = 2
    ds.SeriesDescription = "PET-like phantom"
    ds.InstanceNumber = k + 1
    ds.ImageOrientationPatient = [float(v) for v in (*row_dir, *col_dir)]
    ds.ImagePositionPatient = [float(v) for v in origin + lps[:, 2] * k]
    ds.SliceLocation = float(ds.ImagePositionPatient[2])
    ds.PixelSpacing = [float(spacing[1]), float(spacing[0])]  # row spacing, column spacing
    ds.SliceThickness = float(spacing[2])
    ds.Units = "BQML"
    ds.CorrectedImage = ["ATTN", "DECY"]
    ds.DecayCorrection = "START"
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.Rows, ds.Columns = data.shape[1], data.shape[0]
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 0
    ds.RescaleIntercept, ds.RescaleSlope = 0, f"{slope:.6g}"
    # Rows run along j (the column direction), columns along i.
    pixels = np.round(data[:, :, k].T / float(ds.RescaleSlope)).clip(0, 65535).astype("<u2")
    ds.PixelData = pixels.tobytes()
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.save_as(os.path.join(out, f"PT{k + 1:04d}.dcm"), write_like_original=False)
print(f"{data.shape[2]} PT instances, series {series_uid}")
