#!/usr/bin/env python3
"""The viewer's sphere statistics (roi-stats) against `mvw stats --sphere --json` for the same
sphere: the voxel count exactly, volume, max, mean, SD and SUVpeak to 1e-6 (relative above 1).
usage: compare-roi-stats.py VIEWER_JSON INDEX anatomical|functional STATS_JSON"""
import json
import sys

viewer_file, index, which, stats_file = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
viewer = json.load(open(viewer_file))[index][which]
stats = json.load(open(stats_file))[0]
problems = []
if viewer.get("voxels") != stats["voxels"]:
    problems.append(f"voxels {viewer.get('voxels')} != {stats['voxels']}")
if viewer.get("unit") != stats["unit"]:
    problems.append(f"unit {viewer.get('unit')!r} != {stats['unit']!r}")
for key in ("volume_ml", "max", "mean", "sd", "peak"):
    if (key in stats) != (key in viewer):
        problems.append(f"{key}: in mvw stats {key in stats}, in the viewer {key in viewer}")
        continue
    if key in stats:
        a, b = viewer[key], stats[key]
        if abs(a - b) > 1e-6 * max(1.0, abs(b)):
            problems.append(f"{key} {a!r} != {b!r}")
if problems:
    print(f"FAIL: {which} statistics of sphere {index} differ from mvw stats: " + "; ".join(problems))
    sys.exit(1)
shown = ", ".join(f"{k} {stats[k]:.6g}" for k in ("voxels", "volume_ml", "max", "mean", "sd", "peak")
                  if k in stats)
print(f"{which} sphere {index}: viewer == mvw stats ({shown} {stats['unit']})")
