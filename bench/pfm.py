"""Reading the colour PFM images `whisker --out-float x.pfm` writes, for the
bench's Python scripts (error_by_region.py, error_spectrum.py)."""
import struct
import sys


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
