#!/usr/bin/env bash
# The denoiser against a converged Whisker reference, at every scale
# (bench/denoise_error.py): for each sample count, a render with
# --out-denoised, its raw and denoised errors at 1-16 px, and how its own
# estimate compares with the true error; at the end the denoised/raw ratios
# as a Markdown table.
#
#   bench/denoise_error.sh [BUILD] [SCENE] [REF_SPP] [SPP...]
#   e.g. bench/denoise_error.sh build cat 1024 4 16 64
#
# The reference (two seeds of REF_SPP) is cached in $BUILD/references/.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
scene=${2:-cat}
ref_spp=${3:-1024}
shift $(( $# < 3 ? $# : 3 ))
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(4 16 64)
bin=$build/whisker
refs=$build/references
mkdir -p "$refs"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for seed in 101 102; do
  ref=$refs/$scene-$ref_spp-seed$seed.pfm
  [ -f "$ref" ] || "$bin" --headless --quiet --scene "$scene" --target-spp "$ref_spp" --seed "$seed" \
    --out-float "$ref" >/dev/null
done
table="| filter, spp | 1 px | 2 px | 4 px | 8 px | 16 px |
|---|---|---|---|---|---|"
for filter in quality fast; do
  for n in "${counts[@]}"; do
    echo "--- $scene, $n spp, $filter filter"
    "$bin" --headless --quiet --scene "$scene" --target-spp "$n" --seed 1 --out-float "$work/raw.pfm" \
      --out-denoised "$work/dn.pfm" --denoiser "$filter" --stats "$work/s.json" | head -1
    python3 "$here/denoise_error.py" "$refs/$scene-$ref_spp-seed101.pfm" \
      "$refs/$scene-$ref_spp-seed102.pfm" "$work/raw.pfm" "$work/dn.pfm" "$work/s.json" | tee "$work/e.txt"
    # The denoised/raw column, one row of the summary.
    table+=$'\n'"| $filter, $n |$(awk 'NR > 1 { printf " %.2f |", $5 }' "$work/e.txt")"
  done
done
echo "--- denoised/raw error, $scene against 2 x $ref_spp spp"
echo "$table"
