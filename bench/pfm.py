"""Reading and writing the colour PFM images `whisker --out-float x.pfm`
writes, for the bench's Python scripts (error_by_region.py,
error_spectrum.py, denoise_error.py, cat_target.sh's reference)."""
import struct
import sys
import zlib


def read_pfm(path, tool):
    """(width, height, values): the colour values as stored (rows bottom to
    top, three per pixel), as floats. Exits with a message naming `tool` and
    the file on a missing or malformed file."""
    try:
        with open(path, "rb") as f:
            kind = f.readline().strip()
            if kind != b"PF":
                sys.exit(f"{tool}: {path}: not a colour PFM (header {kind[:16]!r})")
            try:
                width, height = map(int, f.readline().split())
                scale = float(f.readline())
            except ValueError:
                sys.exit(f"{tool}: {path}: malformed PFM header")
            data = f.read()
    except OSError as e:
        sys.exit(f"{tool}: {path}: {e.strerror}")
    count = width * height * 3
    if width <= 0 or height <= 0 or len(data) != 4 * count:
        sys.exit(f"{tool}: {path}: {len(data)} bytes of data, expected {4 * count} for {width}x{height}")
    return width, height, struct.unpack(("<" if scale < 0 else ">") + f"{count}f", data)


def write_pfm(path, width, height, values):
    """A colour PFM of `values` (rows bottom to top, as read_pfm gives them),
    little-endian float32."""
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(struct.pack(f"<{len(values)}f", *values))


def write_png(path, rows):
    """An 8-bit RGB PNG of rows (top to bottom) of (r, g, b) in 0-255,
    standard library only."""
    raw = b"".join(b"\0" + bytes(v for px in row for v in px) for row in rows)
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data
                                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n"
                + chunk(b"IHDR", struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def png(argv):
    """pfm.py png IMAGE.pfm OUT.png [REFERENCE.pfm GAIN] [--crop X,Y,W,H]: the
    image in the report's mapping, min(255, 255 L^(1/2.2)) with L in display
    white (255^2.2 radiance); with a reference, |IMAGE - REFERENCE| per channel
    times GAIN in the same mapping. X, Y from the top left."""
    crop = None
    if "--crop" in argv:
        k = argv.index("--crop")
        crop = [int(v) for v in argv[k + 1].split(",")]
        del argv[k:k + 2]
    if len(argv) not in (2, 4):
        sys.exit(png.__doc__)
    w, h, v = read_pfm(argv[0], "pfm.py")
    gain, ref = 1.0, None
    if len(argv) == 4:
        wr, hr, ref = read_pfm(argv[2], "pfm.py")
        if (wr, hr) != (w, h):
            sys.exit(f"pfm.py: {argv[2]} is {wr}x{hr}, {argv[0]} is {w}x{h}")
        gain = float(argv[3])
    x0, y0, cw, ch = crop or (0, 0, w, h)
    white = 255.0 ** 2.2
    rows = []
    for y in range(y0, y0 + ch):
        base = 3 * (h - 1 - y) * w  # PFM rows bottom to top
        row = []
        for x in range(x0, x0 + cw):
            i = base + 3 * x
            px = [v[i + c] if ref is None else gain * abs(v[i + c] - ref[i + c]) for c in range(3)]
            row.append(tuple(min(255, int(255 * max(0.0, p / white) ** (1 / 2.2) + 0.5)) for p in px))
        rows.append(row)
    write_png(argv[1], rows)


if __name__ == "__main__":
    # pfm.py mean A.pfm B.pfm OUT.pfm: the mean of two images of one size
    # (cat_target.sh's reference from two seeds); pfm.py png ...: see png().
    if len(sys.argv) > 1 and sys.argv[1] == "png":
        png(sys.argv[2:])
        sys.exit(0)
    if len(sys.argv) != 5 or sys.argv[1] != "mean":
        sys.exit("usage: pfm.py mean A.pfm B.pfm OUT.pfm | pfm.py png ...")
    (wa, ha, a), (wb, hb, b) = (read_pfm(p, "pfm.py") for p in sys.argv[2:4])
    if (wa, ha) != (wb, hb):
        sys.exit(f"pfm.py: {sys.argv[2]} is {wa}x{ha}, {sys.argv[3]} is {wb}x{hb}")
    write_pfm(sys.argv[4], wa, ha, [(x + y) / 2 for x, y in zip(a, b)])
