#!/usr/bin/env bash
# whisker-bench make-rays: the cat's primary set is one unit ray per pixel
# of 512 x 512 from the report's camera, and the diffuse set 8 unit rays per
# primary ray that hits the cat, starting 1e-3 off it.
#   make_rays_test.sh WHISKER_BENCH
set -euo pipefail
bench=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$bench" make-rays "$dir" --seed 7 >/dev/null
hits=$("$bench" rays "$dir/cat_primary.rays" --no-embree --reps 1 --threads 1 --json |
  python3 -c "import json, sys; j = json.load(sys.stdin); assert j['rays'] == 512 * 512, j; print(j['hits'])")
diffuse=$("$bench" rays "$dir/cat_diffuse.rays" --no-embree --reps 1 --threads 1 --json)
python3 - "$dir" "$hits" "$diffuse" <<'PY'
import json, math, struct, sys
folder, hits, diffuse = sys.argv[1], int(sys.argv[2]), json.loads(sys.argv[3])
def records(name):
    data = open(f"{folder}/{name}", "rb").read()
    assert len(data) % 28 == 0, name
    return [struct.unpack_from("<7f", data, k) for k in range(0, len(data), 28)]
primary, bounce = records("cat_primary.rays"), records("cat_diffuse.rays")
assert 0 < hits < len(primary), hits
assert len(bounce) == 8 * hits, (len(bounce), hits)
# Pixel (i, j) looks along (j - 255.5, 255.5 - i, -256 / tan 30 deg) from (0, 0, 55).
depth = 256 / math.tan(math.radians(30))
for i, j in [(0, 0), (0, 511), (255, 256), (511, 3), (300, 200)]:
    r = primary[512 * i + j]
    d = (j - 255.5, 255.5 - i, -depth)
    n = math.sqrt(sum(c * c for c in d))
    assert r[:3] == (0.0, 0.0, 55.0) and r[6] == math.inf, r
    assert all(abs(r[3 + k] - d[k] / n) < 1e-6 for k in range(3)), (i, j, r)
for r in primary + bounce:
    assert abs(math.sqrt(r[3] ** 2 + r[4] ** 2 + r[5] ** 2) - 1) < 1e-5, r
# The bounces leave the cat from its outside: most escape it (4 % of them
# meet it again here), and those that meet it do so far past the 1e-3
# offset. Started inside, or turned into the surface, nearly all would hit
# it at about 1e-3.
assert 0 < diffuse["hits"] < 0.25 * len(bounce), diffuse
assert diffuse["distance_sum"] > 0.1 * diffuse["hits"], diffuse
# Each of a hit's 8 shares its origin and has a direction of its own.
for k in range(0, len(bounce), 8):
    assert len({r[:3] for r in bounce[k:k + 8]}) == 1 and len({r[3:6] for r in bounce[k:k + 8]}) == 8
print("ok", len(primary), hits, len(bounce))
PY
