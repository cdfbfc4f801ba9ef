#!/usr/bin/env python3
"""Pixels of a PNG within 40 (per channel) of an RGB colour: the viewer's ROI circles and rulers.
usage: pngcolour.py FILE R G B [X0]   (X0: only columns from X0 on, e.g. the panes)"""
import sys

import imageio
import numpy as np

img = imageio.imread(sys.argv[1])[..., :3].astype(int)
if len(sys.argv) > 5:
    img = img[:, int(sys.argv[5]):]
rgb = np.array([int(v) for v in sys.argv[2:5]])
print(int((np.abs(img - rgb).max(axis=2) <= 40).sum()))
