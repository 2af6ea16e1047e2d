#!/usr/bin/env bash
# bench/error_by_region.py on two 4 x 2 images made here, whose errors are
# known: the regions by the channels the mean image holds, each one's share
# of the pixels and of the error, and the error by channel; then bad input;
# then --places (the cat's hard places) on a small room of known error.
#   error_by_region_test.sh SCRIPT
set -euo pipefail
script=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 - "$dir" <<'PY'
import struct, sys
W = 255.0 ** 2.2
def write(path, pixels, width=4, height=2, order="<"):
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n%s\n" % (width, height, b"-1.0" if order == "<" else b"1.0"))
        f.write(struct.pack(order + "%df" % (3 * len(pixels)), *[v * W for p in pixels for v in p]))
# Four blue pixels (one of them dark in both: still "B" by its mean), two
# green, one white, one black in both images.
a = [(0, 0, 1.0), (0, 0, 2.0), (0, 0, 0.5), (0, 0, 1.0), (0, 0.2, 0), (0, 0.3, 0), (1, 1, 1), (0, 0, 0)]
b = [(0, 0, 0.8), (0, 0, 2.0), (0, 0, 0.1), (0, 0, 0.0), (0, 0.1, 0), (0, 0.3, 0), (1.2, 1, 0.8), (0, 0, 0)]
write(f"{sys.argv[1]}/a.pfm", a)
write(f"{sys.argv[1]}/b.pfm", b, order=">")  # big-endian: the scale's sign says so
write(f"{sys.argv[1]}/small.pfm", a[:4], width=2, height=2)
PY
python3 "$script" "$dir/a.pfm" "$dir/b.pfm" --json "$dir/out.json" >"$dir/out.txt"
python3 - "$dir/out.json" <<'PY'
import json, math, sys
out = json.load(open(sys.argv[1]))
# Squared differences (a - b)^2 per value (one image: half of each): blue pixels
# 0.04, 0, 0.16, 1.0 (sum 1.2) in blue; green 0.01 in green; white 0.04 in
# red and 0.04 in blue. Total 1.29 over 24 values. (The files hold float32.)
close = lambda x, y: math.isclose(x, y, rel_tol=1e-6, abs_tol=1e-9)
assert close(out["mse"], 1.29 / 2 / 24), out["mse"]
regions = {r["region"]: r for r in out["regions"]}
assert set(regions) == {"B", "G", "RGB", "none"}, regions.keys()
assert [r["region"] for r in out["regions"]][:3] == ["B", "RGB", "G"], out["regions"]
expect = {"B": (4, 1.2, [0, 0, 1]), "G": (2, 0.01, [0, 1, 0]), "RGB": (1, 0.08, [0.5, 0, 0.5]), "none": (1, 0, [0, 0, 0])}
for name, (pixels, se, channels) in expect.items():
    r = regions[name]
    assert close(r["pixel_share"], pixels / 8), (name, r)
    assert close(r["error_share"], se / 1.29), (name, r)
    if pixels and se:
        assert close(r["mse_per_pixel_over_image"], (se / pixels) / (1.29 / 8)), (name, r)
    assert all(close(x, y) for x, y in zip(r["channel_share"], channels)), (name, r)
assert all(close(x, y) for x, y in zip(regions["B"]["mean"], [0, 0, (0.9 + 2 + 0.3 + 0.5) / 4])), regions["B"]
assert all(close(x, y) for x, y in zip(out["channel_share"], [0.04 / 1.29, 0.01 / 1.29, 1.24 / 1.29])), out
PY
grep -q "^B  *50.0%  93.0%" "$dir/out.txt" || { cat "$dir/out.txt"; echo "text table wrong"; exit 1; }
# Bad input: a clear message naming the file, a non-zero exit.
expect_fail() {  # pattern args...
  local pattern=$1
  shift
  if python3 "$script" "$@" >"$dir/err.txt" 2>&1; then
    echo "accepted: $*"; exit 1
  fi
  grep -q "$pattern" "$dir/err.txt" || { echo "message for $*:"; cat "$dir/err.txt"; exit 1; }
}
expect_fail "error_by_region: .*missing.pfm: No such file" "$dir/missing.pfm" "$dir/b.pfm"
expect_fail "error_by_region: .*a.pfm is 4x2, .*small.pfm is 2x2" "$dir/a.pfm" "$dir/small.pfm"
head -c 40 "$dir/a.pfm" >"$dir/cut.pfm"
expect_fail "cut.pfm: .* expected 96" "$dir/a.pfm" "$dir/cut.pfm"
printf 'P6\n1 1\n255\nabc' >"$dir/ppm.pfm"
expect_fail "ppm.pfm: not a colour PFM" "$dir/ppm.pfm" "$dir/a.pfm"
expect_fail "A.pfm B.pfm" "$dir/a.pfm"
expect_fail "error_by_region: --json needs a file name" "$dir/a.pfm" "$dir/b.pfm" --json

# --places on a 32 x 32 room made here (rows top to bottom): a green wall,
# a blue floor from row 20, a white block (the cat) at rows 8-21, columns
# 4-19, and a 1-px white line (a whisker) at row 6, columns 23-27 (right of
# x = 370/512 of the width, above 240/512). The references are one image
# twice (no noise of their own); the image under test is the reference
# plus 0.1 display white in every channel of the whisker's pixels (red
# kept 1.1, MSE 0.01 there) and nothing elsewhere.
python3 - "$dir" <<'PY'
import struct, sys
W = 255.0 ** 2.2
def write(path, rows):
    with open(path, "wb") as f:
        f.write(b"PF\n32 32\n-1.0\n")
        f.write(struct.pack("<%df" % (3 * 32 * 32), *[v * W for row in rows[::-1] for p in row for v in p]))
ref = [[(0, 0.3, 0) if y < 20 else (0, 0, 2.0) for x in range(32)] for y in range(32)]
for y in range(8, 22):
    for x in range(4, 20):
        ref[y][x] = (1.0, 1.0, 1.0)
for x in range(23, 28):
    ref[6][x] = (0.5, 0.6, 0.5)
img = [row[:] for row in ref]
for x in range(23, 28):
    img[6][x] = tuple(v + 0.1 for v in ref[6][x])
write(f"{sys.argv[1]}/ref.pfm", ref)
write(f"{sys.argv[1]}/img.pfm", img)
PY
python3 "$script" --places "$dir/ref.pfm" "$dir/ref.pfm" "$dir/ref.pfm" "$dir/img.pfm" "$dir/ref.pfm" \
  --json "$dir/places.json" --masks "$dir/places.png" >"$dir/places.txt"
python3 - "$dir/places.json" "$dir/places.png" <<'PY'
import json, math, sys
out = json.load(open(sys.argv[1]))
close = lambda x, y: math.isclose(x, y, rel_tol=1e-5, abs_tol=1e-12)
assert out["places"]["whiskers"] == 5 and out["places"]["cat"] == 14 * 16 + 5, out["places"]
assert out["places"]["silhouette"] > 0 and out["places"]["hot spot"] > 0, out["places"]
img, ref = out["images"]
assert close(img["mse"]["whiskers"], 0.01), img
assert close(img["mse"]["image"], 5 * 0.01 / 1024), img
assert close(img["whiskers_red_kept"], 1.2), img  # red 0.6 over 0.5
assert all(close(v, 0) for v in ref["mse"].values() if v == v) and close(ref["whiskers_red_kept"], 1), ref
assert open(sys.argv[2], "rb").read(8) == b"\x89PNG\r\n\x1a\n"
PY
echo "error_by_region: regions, shares, the hard places and bad input as expected"
