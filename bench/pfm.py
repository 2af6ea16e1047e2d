"""Reading and writing the colour PFM images `whisker --out-float x.pfm`
writes, for the bench's Python scripts (error_by_region.py,
error_spectrum.py, denoise_error.py, cat_target.sh's reference)."""
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


def write_pfm(path, width, height, values):
    """A colour PFM of `values` (rows bottom to top, as read_pfm gives them),
    little-endian float32."""
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(struct.pack(f"<{len(values)}f", *values))


if __name__ == "__main__":
    # pfm.py mean A.pfm B.pfm OUT.pfm: the mean of two images of one size
    # (cat_target.sh's reference from two seeds).
    if len(sys.argv) != 5 or sys.argv[1] != "mean":
        sys.exit("usage: pfm.py mean A.pfm B.pfm OUT.pfm")
    (wa, ha, a), (wb, hb, b) = (read_pfm(p, "pfm.py") for p in sys.argv[2:4])
    if (wa, ha) != (wb, hb):
        sys.exit(f"pfm.py: {sys.argv[2]} is {wa}x{ha}, {sys.argv[3]} is {wb}x{hb}")
    write_pfm(sys.argv[4], wa, ha, [(x + y) / 2 for x, y in zip(a, b)])
