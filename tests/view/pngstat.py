#!/usr/bin/env python3
"""Small PNG facts for the viewer test, standard library only.
usage: pngstat.py FILE                 -> "W H distinct_colours yellow_pixels"
       pngstat.py --differ A B         -> exit 0 if the two images differ in any pixel
       pngstat.py --changed A B        -> "N" pixels that differ (same size, else exit 1)
       pngstat.py --crosshair-only A B -> exit 0 if A and B are the same size and every pixel
                                          that differs lies within 3 rows and 3 columns (the
                                          MPR crosshair's antialiased lines); prints "N"
       pngstat.py --bar-only SHOT RAW  -> exit 0 if every pixel that differs lies where a colour
                                          bar is drawn (render::drawBar: the right edge, from a
                                          quarter to three quarters of the height, with its
                                          labels) and some do: the viewer's grey bar that
                                          `mvw render` does not draw; prints "N"
       pngstat.py --labels SHOT RAW    -> "left right top bottom": label-yellow pixels that SHOT
                                          (a pane as shown) has and RAW (its render) has not, in
                                          the four places the orientation labels go"""
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


def pixels(img):
    w, h, bpp, rows = img
    return [[tuple(row[x:x + 3]) for x in range(0, w * bpp, bpp)] for row in rows]


def changed(a, b):
    if a[:2] != b[:2]:
        print("sizes differ: %dx%d and %dx%d" % (a[0], a[1], b[0], b[1]))
        sys.exit(1)
    pa, pb = pixels(a), pixels(b)
    return [(x, y) for y in range(a[1]) for x in range(a[0]) if pa[y][x] != pb[y][x]]


def label_yellow(p):  # annotations' (255, 230, 60), antialiased against black
    r, g, b = p
    return r > 150 and g > 0.8 * r and b < 0.45 * r


def main():
    if sys.argv[1] == "--differ":
        a, b = read(sys.argv[2]), read(sys.argv[3])
        sys.exit(0 if a[3] != b[3] else 1)
    if sys.argv[1] == "--changed":
        print(len(changed(read(sys.argv[2]), read(sys.argv[3]))))
        sys.exit(0)
    if sys.argv[1] == "--crosshair-only":
        diff = changed(read(sys.argv[2]), read(sys.argv[3]))
        print(len(diff))
        if not diff:
            sys.exit(0)
        col = max(set(x for x, _ in diff), key=[x for x, _ in diff].count)
        row = max(set(y for _, y in diff), key=[y for _, y in diff].count)
        stray = [(x, y) for x, y in diff if abs(x - col) > 1 and abs(y - row) > 1]
        if stray:
            print("%d pixels differ off the crosshair (column %d, row %d), first at %s" %
                  (len(stray), col, row, stray[0]))
            sys.exit(1)
        sys.exit(0)
    if sys.argv[1] == "--bar-only":
        a = read(sys.argv[2])
        diff = changed(a, read(sys.argv[3]))
        print(len(diff))
        w, h = a[0], a[1]
        scale = max(0.4, min(w, h) / 600.0)
        # drawBar's bar starts 14 + 44 (scaled) from the right edge; its title (a volume's
        # name, up to 24 characters) may reach a third of a small pane further left.
        left = min(w - (14 + 44 + 90) * scale, w * 0.55)
        top, bottom = h / 4 - 40 * scale, h * 3 / 4 + 45 * scale
        stray = [(x, y) for x, y in diff if x < left or y < top or y > bottom]
        if stray:
            print("%d pixels differ outside the colour bar, first at %s" % (len(stray), stray[0]))
            sys.exit(1)
        sys.exit(0 if diff else 1)
    if sys.argv[1] == "--labels":
        shot, raw = read(sys.argv[2]), read(sys.argv[3])
        if shot[:2] != raw[:2]:
            print("sizes differ")
            sys.exit(1)
        w, h = shot[0], shot[1]
        ps, pr = pixels(shot), pixels(raw)
        # Where annotate() puts the labels: mid-left, mid-right, top centre, bottom centre; the
        # caption (above the bottom label) and the scale bar (bottom right) stay outside.
        s = max(0.4, min(w, h) / 600.0)
        pad, lh = int(8 * s), int(30 * s)
        boxes = [(0, h // 2 - lh, 4 * lh, h // 2 + lh), (w - 4 * lh, h // 2 - lh, w, h // 2 + lh),
                 (w // 2 - 2 * lh, 0, w // 2 + 2 * lh, pad + lh), (w // 2 - 2 * lh, h - pad - lh // 2,
                                                                    w // 2 + 2 * lh, h)]
        counts = []
        for x0, y0, x1, y1 in boxes:
            counts.append(sum(1 for y in range(y0, y1) for x in range(x0, x1)
                              if label_yellow(ps[y][x]) and not label_yellow(pr[y][x])))
        print(*counts)
        sys.exit(0)
    w, h, bpp, rows = read(sys.argv[1])
    colours, yellow = set(), 0
    for row in rows[::2]:
        for x in range(0, w * bpp, bpp * 2):
            r, g, b = row[x], row[x + 1], row[x + 2]
            colours.add((r, g, b))
            yellow += r > 200 and g > 180 and b < 120
    print(w, h, len(colours), yellow)


if __name__ == "__main__":
    main()
