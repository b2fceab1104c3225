#!/usr/bin/env python3
"""Screenshot checks of the browser test (tests/browser/run_browser_test.sh).

  png_compare.py size FILE.png W H      the image is W x H and not blank
  png_compare.py same A.png B.png       A and B show the same layout

"Not blank": at least 2 % of the pixels differ from the page background
(the most frequent colour). "Same layout": both are cut into 40 x 40 pixel
cells and each cell's ink (share of non-background pixels) is compared,
allowing one cell of vertical drift (line heights differ slightly between
browsers): the ink maps, averaged over 3 cell rows, must correlate (Pearson
r >= 0.9) and at most 2 % of the cells may be inked in one and empty in
the other and its vertical neighbours. Font rendering differs between
browsers; a moved, missing or resized plot does not pass.
Only the Python standard library (zlib) is used: 8-bit RGB/RGBA/grey PNGs.
"""
import struct
import sys
import zlib


def read_png(path):
    try:
        data = open(path, "rb").read()
    except OSError as e:
        raise SystemExit(f"{path}: {e.strerror}")
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG file")
    pos, idat, w, h, ctype, depth, interlace = 8, b"", 0, 0, 0, 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
    if depth != 8 or channels is None or interlace:
        raise SystemExit(f"{path}: unsupported PNG (depth {depth}, colour type {ctype})")
    raw = zlib.decompress(idat)
    stride = w * channels
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = prev[x]
            c = prev[x - channels] if x >= channels else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + ((a + b) >> 1)) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    # grey value per pixel (alpha ignored)
    grey = []
    for line in rows:
        if channels >= 3:
            grey.append([(line[i] + line[i + 1] + line[i + 2]) // 3
                         for i in range(0, stride, channels)])
        else:
            grey.append([line[i] for i in range(0, stride, channels)])
    return w, h, grey


def background(grey):
    counts = {}
    for line in grey[::7]:
        for v in line[::7]:
            counts[v] = counts.get(v, 0) + 1
    return max(counts, key=counts.get)


def ink_map(grey, cell=40):
    bg = background(grey)
    h, w = len(grey), len(grey[0])
    cells = []
    for cy in range(0, h - cell + 1, cell):
        for cx in range(0, w - cell + 1, cell):
            n = 0
            for y in range(cy, cy + cell, 2):
                row = grey[y]
                for x in range(cx, cx + cell, 2):
                    if abs(row[x] - bg) > 24:
                        n += 1
            cells.append(n / (cell * cell / 4))
    return cells


def compare(a, b, cols):
    rows = len(a) // cols
    at = lambda m, y, x: m[min(max(y, 0), rows - 1) * cols + x]
    smooth = lambda m: [sum(at(m, y + k, x) for k in (-1, 0, 1)) / 3
                        for y in range(rows) for x in range(cols)]
    sa, sb = smooth(a), smooth(b)
    n = len(sa)
    ma, mb = sum(sa) / n, sum(sb) / n
    cov = sum((x - ma) * (y - mb) for x, y in zip(sa, sb))
    va = sum((x - ma) ** 2 for x in sa)
    vb = sum((y - mb) ** 2 for y in sb)
    r = cov / (va * vb) ** 0.5 if va > 0 and vb > 0 else 0.0
    lonely = 0
    for y in range(rows):
        for x in range(cols):
            for m, o in ((a, b), (b, a)):
                if at(m, y, x) > 0.02 and max(at(o, y + k, x) for k in (-1, 0, 1)) <= 0.02:
                    lonely += 1
    return r, lonely / n


def main(argv):
    if len(argv) == 5 and argv[1] == "size":
        w, h, grey = read_png(argv[2])
        if (w, h) != (int(argv[3]), int(argv[4])):
            print(f"{argv[2]}: {w} x {h}, expected {argv[3]} x {argv[4]}")
            return 1
        cells = ink_map(grey)
        ink = sum(cells) / max(1, len(cells))
        if ink < 0.02:
            print(f"{argv[2]}: blank ({100 * ink:.2f} % ink)")
            return 1
        print(f"{argv[2]}: {w} x {h}, {100 * ink:.1f} % ink")
        return 0
    if len(argv) == 4 and argv[1] == "same":
        wa, ha, ga = read_png(argv[2])
        wb, hb, gb = read_png(argv[3])
        if (wa, ha) != (wb, hb):
            print(f"sizes differ: {wa} x {ha} and {wb} x {hb}")
            return 1
        r, lonely = compare(ink_map(ga), ink_map(gb), wa // 40)
        ok = r >= 0.9 and lonely <= 0.02
        print(f"layout correlation r = {r:.3f}, cells inked in one only {100 * lonely:.1f} %: "
              f"{'same' if ok else 'DIFFERENT'}")
        return 0 if ok else 1
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
