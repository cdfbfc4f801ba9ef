#!/usr/bin/env python3
"""Small PNG facts for the viewer test, standard library only.
usage: pngstat.py FILE                 -> "W H distinct_colours yellow_pixels"
       pngstat.py --differ A B         -> exit 0 if the two images differ in any pixel"""
import struct
import sys
import zlib


def read(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        kind, chunk = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", chunk[:10])
            assert depth == 8 and colour in (2, 6), path + ": expected 8-bit RGB(A)"
            bpp = 4 if colour == 6 else 3
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


if sys.argv[1] == "--differ":
    a, b = read(sys.argv[2]), read(sys.argv[3])
    sys.exit(0 if a[3] != b[3] else 1)
w, h, bpp, rows = read(sys.argv[1])
colours, yellow = set(), 0
for row in rows[::2]:
    for x in range(0, w * bpp, bpp * 2):
        r, g, b = row[x], row[x + 1], row[x + 2]
        colours.add((r, g, b))
        yellow += r > 200 and g > 180 and b < 120
print(w, h, len(colours), yellow)
