#!/usr/bin/python3
"""Independent check of `mvw stats` on the real whole-body FDG PET and its DICOM SEG.

Reads the PET slices and the SEG with pydicom + numpy only (no mvw code): SUVbw from the tags,
each voxel's world position from its own slice's ImagePositionPatient, the SEG's bits unpacked
and each PET voxel matched to the nearest SEG frame pixel. Computes voxels, volume, max, mean,
SD, SUVpeak (1 cm^3 sphere, by shifted sums) and the metabolic volume for a sphere at the
hottest voxel, a box around it and both segments, and compares with `mvw stats --json`.
Bad input (exit 2, one message) is checked too.

usage: pet_stats_check.py MVW SHARED_DATA_DIR
"""
import glob
import json
import os
import subprocess
import sys

import numpy as np
import pydicom

PEAK_RADIUS = 6.204
failures = []


def check(what, ok, detail=""):
    print(("ok    " if ok else "FAIL  ") + what + (" " + detail if detail else ""))
    if not ok:
        failures.append(what)


def close(what, mine, theirs, rel=2e-5, absolute=1e-6):
    ok = abs(mine - theirs) <= absolute + rel * abs(mine)
    check(what, ok, "python %.6f  mvw %.6f" % (mine, theirs))


def seconds(tm):
    tm = str(tm)
    return int(tm[0:2]) * 3600 + int(tm[2:4]) * 60 + float(tm[4:] or 0)


mvw, shared = sys.argv[1], sys.argv[2]
folder = os.path.join(shared, "pet-fdg-wholebody")
seg_file = os.path.join(folder, "tumour-segmentation.dcm")

# --- the PET, SUVbw from the tags ----------------------------------------------------------
slices = [pydicom.dcmread(f) for f in sorted(glob.glob(os.path.join(folder, "PET_*.dcm")))]
iop = np.array(slices[0].ImageOrientationPatient, float)
row_dir, col_dir = iop[:3], iop[3:]
normal = np.cross(row_dir, col_dir)
slices.sort(key=lambda d: float(np.dot(np.array(d.ImagePositionPatient, float), normal)))
ipp = np.array([d.ImagePositionPatient for d in slices], float)
row_spacing, col_spacing = (float(x) for x in slices[0].PixelSpacing)  # between rows, columns
depths = ipp @ normal
dz = float(np.median(np.diff(depths)))
voxel_ml = row_spacing * col_spacing * dz / 1000.0

first = slices[0]
drug = first.RadiopharmaceuticalInformationSequence[0]
assert first.Units == "BQML" and first.DecayCorrection == "START"
elapsed = seconds(first.SeriesTime) - seconds(drug.RadiopharmaceuticalStartTime)
decayed_dose = float(drug.RadionuclideTotalDose) * 2.0 ** (-elapsed / float(drug.RadionuclideHalfLife))
suv_factor = float(first.PatientWeight) * 1000.0 / decayed_dose
pet = np.stack([d.pixel_array.astype(np.float64) * float(d.RescaleSlope) + float(d.RescaleIntercept)
                for d in slices]) * suv_factor  # [k, j, i]
nk, nj, ni = pet.shape
kk, jj, ii = np.meshgrid(np.arange(nk), np.arange(nj), np.arange(ni), indexing="ij")
world = (ipp[kk] + ii[..., None] * col_spacing * row_dir + jj[..., None] * row_spacing * col_dir)
print("PET %d x %d x %d, SUVbw factor %.6g, max %.4f" % (ni, nj, nk, suv_factor, pet.max()))
close("SUVbw max", pet.max(), 19.51, absolute=0.01)

# SUVpeak: mean over the 1 cm^3 sphere around every voxel (inside the volume), by shifted sums.
r = int(np.ceil(PEAK_RADIUS / min(row_spacing, col_spacing, dz))) + 1
sums = np.zeros_like(pet)
counts = np.zeros_like(pet)
for dk in range(-r, r + 1):
    for dj in range(-r, r + 1):
        for di in range(-r, r + 1):
            if (di * col_spacing) ** 2 + (dj * row_spacing) ** 2 + (dk * dz) ** 2 > PEAK_RADIUS ** 2:
                continue
            dst = tuple(slice(max(0, -d), n - max(0, d)) for d, n in zip((dk, dj, di), pet.shape))
            src = tuple(slice(max(0, d), n - max(0, -d)) for d, n in zip((dk, dj, di), pet.shape))
            sums[dst] += pet[src]
            counts[dst] += 1
sphere_mean = sums / counts


def stats(mask, threshold=None, fraction=None):
    values = pet[mask]
    out = {"voxels": int(mask.sum()), "volume_ml": mask.sum() * voxel_ml, "max": values.max(),
           "mean": values.mean(), "sd": values.std(), "peak": sphere_mean[mask].max()}
    if fraction is not None:
        threshold = fraction * values.max()
    if threshold is not None:
        hot = values[values >= threshold]
        out["metabolic_volume_ml"] = hot.size * voxel_ml
        out["metabolic_mean"] = hot.mean()
        out["tlg"] = hot.size * voxel_ml * hot.mean()  # TLG: metabolic volume x its SUVmean
    return out


def run_mvw(*args):
    cmd = [mvw, "stats", folder, "--series", "PET WB", "--json"] + [str(a) for a in args]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        check(" ".join(cmd), False, "exit %d: %s" % (p.returncode, p.stderr.strip()))
        return []
    return json.loads(p.stdout)


def compare(name, mine, theirs):
    check(name + ": voxels", mine["voxels"] == theirs["voxels"],
          "python %d  mvw %d" % (mine["voxels"], theirs["voxels"]))
    check(name + ": unit", theirs["unit"] == "SUVbw", theirs["unit"])
    for key in ("volume_ml", "max", "mean", "sd", "peak", "metabolic_volume_ml", "metabolic_mean",
                "tlg"):
        if key in mine:
            close(name + ": " + key, mine[key], theirs.get(key, float("nan")))


def boundary_margin(distance, limit):
    return float(np.min(np.abs(distance - limit)))


# --- a sphere at the hottest voxel ---------------------------------------------------------
hot = np.unravel_index(np.argmax(pet), pet.shape)
centre = world[hot]
distance = np.linalg.norm(world - centre, axis=-1)
# A radius near 15 mm with no voxel centre within 0.05 mm of the surface (mvw's geometry and
# this script's per-slice positions differ by rounding only).
radius = next(r for r in np.arange(15.0, 16.0, 0.05) if boundary_margin(distance, r) > 0.05)
print("hottest voxel (k, j, i) = %s at %s mm LPS; radius %.2f mm, nearest voxel centre %.3f mm "
      "from the surface" % (hot, np.round(centre, 3), radius, boundary_margin(distance, radius)))
sphere = distance <= radius
mine = stats(sphere, fraction=0.41)
theirs = run_mvw("--sphere", *centre, radius, "--threshold-fraction", 0.41)
if theirs:
    compare("sphere r %.2f mm at the hottest voxel" % radius, mine, theirs[0])

# --- a box around it, off the voxel centres ------------------------------------------------
lo = centre - np.array([30.3, 25.1, 40.2])
hi = centre + np.array([20.2, 35.0, 11.0])
box = np.all((world >= lo) & (world <= hi), axis=-1)
check("box faces off the voxel centres",
      min(boundary_margin(world[..., a], lo[a]) for a in range(3)) > 0.05 and
      min(boundary_margin(world[..., a], hi[a]) for a in range(3)) > 0.05)
mine = stats(box, threshold=2.5)
theirs = run_mvw("--box", *lo, *hi, "--threshold", 2.5)
if theirs:
    compare("box around the hottest voxel", mine, theirs[0])

# --- the SEG's segments, each PET voxel matched to the nearest SEG frame pixel ---------------
seg = pydicom.dcmread(seg_file)
assert seg.SOPClassUID == "1.2.840.10008.5.1.4.1.1.66.4" and seg.SegmentationType == "BINARY"
check("SEG on the PET's frame of reference", seg.FrameOfReferenceUID == first.FrameOfReferenceUID)
bits = np.unpackbits(np.frombuffer(seg.PixelData, np.uint8), bitorder="little")
frames = bits[: seg.NumberOfFrames * seg.Rows * seg.Columns].reshape(seg.NumberOfFrames, seg.Rows,
                                                                     seg.Columns)
shared_groups = seg.SharedFunctionalGroupsSequence[0]
seg_iop = np.array(shared_groups.PlaneOrientationSequence[0].ImageOrientationPatient, float)
seg_row, seg_col = seg_iop[:3], seg_iop[3:]
seg_normal = np.cross(seg_row, seg_col)
seg_rs, seg_cs = (float(x) for x in shared_groups.PixelMeasuresSequence[0].PixelSpacing)
seg_step = float(shared_groups.PixelMeasuresSequence[0].SpacingBetweenSlices)
segment_masks = {}
for number in [int(s.SegmentNumber) for s in seg.SegmentSequence]:
    mask = np.zeros(pet.shape, bool)
    for f, group in enumerate(seg.PerFrameFunctionalGroupsSequence):
        if int(group.SegmentIdentificationSequence[0].ReferencedSegmentNumber) != number:
            continue
        fpos = np.array(group.PlanePositionSequence[0].ImagePositionPatient, float)
        # PET voxels whose centre is nearest this frame's plane (within half the SEG's step)
        near = np.abs((world - fpos) @ seg_normal) < seg_step / 2
        rel = world[near] - fpos
        c = np.rint(rel @ seg_row / seg_cs).astype(int)
        rr = np.rint(rel @ seg_col / seg_rs).astype(int)
        inside = (c >= 0) & (c < seg.Columns) & (rr >= 0) & (rr < seg.Rows)
        hit = np.zeros(len(c), bool)
        hit[inside] = frames[f, rr[inside], c[inside]] == 1
        idx = np.argwhere(near)[hit]
        mask[tuple(idx.T)] = True
    segment_masks[number] = mask
names = {int(s.SegmentNumber): str(s.SegmentLabel) for s in seg.SegmentSequence}
print("segment voxels on the PET grid: %s; overlap %d voxels"
      % ({n: int(m.sum()) for n, m in segment_masks.items()},
         int((segment_masks[1] & segment_masks[2]).sum())))
theirs = run_mvw("--labels", seg_file, "--threshold-fraction", 0.41)
check("one object per segment and a total", len(theirs) == len(segment_masks) + 1,
      str(len(theirs)))
total = [o for o in theirs if o.get("total")]
theirs = [o for o in theirs if not o.get("total")]
# The total metabolic tumour volume: the union of each segment's voxels at or above 41 % of its
# own max, a voxel in both segments counted once; TLG = that volume x its SUVmean.
hot_union = np.zeros(pet.shape, bool)
for number, m in segment_masks.items():
    hot_union |= m & (pet >= 0.41 * pet[m].max())
tmtv = hot_union.sum() * voxel_ml
print("python: TMTV %.4f ml, SUVmean %.4f, TLG %.4f" % (tmtv, pet[hot_union].mean(),
                                                       tmtv * pet[hot_union].mean()))
check("a total object", len(total) == 1)
if total:
    t = total[0]
    check("total: metabolic voxels", t["metabolic_voxels"] == int(hot_union.sum()),
          "python %d  mvw %d" % (hot_union.sum(), t["metabolic_voxels"]))
    check("total: voxels (union of the segments)",
          t["voxels"] == int((segment_masks[1] | segment_masks[2]).sum()))
    close("total: TMTV ml", tmtv, t["metabolic_volume_ml"])
    close("total: metabolic_mean", pet[hot_union].mean(), t["metabolic_mean"])
    close("total: tlg", tmtv * pet[hot_union].mean(), t["tlg"])
# The folder opens without --series (its SEG is the segmentation) and the SEG is the default ROI.
p = subprocess.run([mvw, "stats", folder, "--threshold-fraction", "0.41", "--json"],
                   capture_output=True, text=True)
check("the folder without --series or --labels: exit 0", p.returncode == 0, p.stderr.strip())
if p.returncode == 0:
    default = json.loads(p.stdout)
    labelled = run_mvw("--labels", seg_file, "--threshold-fraction", 0.41)
    check("the folder's SEG is the default ROI", default == labelled)
for obj in theirs:
    number = obj["label"]
    check("segment %d name" % number, obj["name"] == names[number], obj["name"])
    mine = stats(segment_masks[number], fraction=0.41)
    compare("segment %d \"%s\"" % (number, names[number]), mine, obj)
    print("  python: %s" % {k: round(float(v), 4) for k, v in mine.items()})
theirs = run_mvw("--labels", seg_file, "--label", 2, "--threshold", 2.5)
if theirs:
    check("--label 2 gives one object", len(theirs) == 1 and theirs[0]["label"] == 2)
    compare("segment 2 alone, SUV 2.5", stats(segment_masks[2], threshold=2.5), theirs[0])

# --- bad input: one message naming the problem, exit 2 -------------------------------------
bad = {
    "sphere outside the volume": ["--sphere", 0, 0, 5000, 10],
    "radius 0": ["--sphere", *centre, 0],
    "negative radius": ["--sphere", *centre, -3],
    "box with min > max": ["--box", *hi, *lo],
    "no ROI": [],
    "two ROIs": ["--sphere", *centre, 10, "--box", *lo, *hi],
    "both thresholds": ["--sphere", *centre, 10, "--threshold", 2.5, "--threshold-fraction", 0.4],
    "unknown label": ["--labels", seg_file, "--label", 7],
    "NaN coordinate": ["--sphere", centre[0], "nan", centre[2], 10],
    "infinite threshold": ["--sphere", *centre, 10, "--threshold", "inf"],
    "fraction above 1": ["--sphere", *centre, 10, "--threshold-fraction", 41],
}
for what, args in bad.items():
    p = subprocess.run([mvw, "stats", folder, "--series", "PET WB"] + [str(a) for a in args],
                       capture_output=True, text=True)
    message = p.stderr.strip()
    check("bad input, %s: exit 2, one message" % what,
          p.returncode == 2 and p.stdout == "" and message != "" and "internal" not in message,
          "(exit %d) %s" % (p.returncode, message.splitlines()[0] if message else ""))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
