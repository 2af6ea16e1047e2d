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
# The reference (two seeds of REF_SPP, REF_SEEDS "101 102") is cached in
# $BUILD/references/.
#
# PLACES=1: the cat's hard places instead (bench/error_by_region.py
# --places): the cat and the glass cat (scene glass-cat) at SPP... (default
# 1 4 16 64), raw and denoised by FILTER (quality), seed 1, each against
# its own scene's reference (the glass cat's of GLASS_REF_SPP, default
# REF_SPP): the MSE over the whole image, the silhouette, the whiskers, the
# contact shadow, the light's hot spot and the cat, then denoised over raw
# per place, and how much of the whiskers' light each image keeps. The
# places are found in a cat render of MASK_SPP (256) with MASK_SEED (9003).
# With PICTURES=DIR, also crops (CROP "288,150,192,192": x, y, width,
# height from the top left) of the raw and denoised cat at 4, 16 and 64 spp
# (those of SPP...), of the reference, and of |image - reference| x GAIN
# (4), as PNG (bench/pfm.py png), and the places' mask.
#
#   PLACES=1 REF_SEEDS="9001 9002" GLASS_REF_SPP=256 PICTURES=docs/images/denoise \
#     bench/denoise_error.sh build cat 512
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
read -r ref_a ref_b <<<"${REF_SEEDS:-101 102}"
# reference SCENE [SPP]: rendered once (SPP, default REF_SPP, both seeds), then cached.
reference() {
  local seed ref spp=${2:-$ref_spp}
  for seed in "$ref_a" "$ref_b"; do
    ref=$refs/$1-$spp-seed$seed.pfm
    [ -f "$ref" ] || { "$bin" --headless --quiet --scene "$1" --target-spp "$spp" --seed "$seed" \
      --out-float "$ref.part.pfm" >/dev/null && mv "$ref.part.pfm" "$ref"; }
  done
}

if [ "${PLACES:-0}" = 1 ]; then
  [ "$#" -gt 0 ] || counts=(1 4 16 64)
  filter=${FILTER:-quality}
  # The places are found in a cat render of their own (MASK_SEED, MASK_SPP).
  mask_ref=$refs/cat-${MASK_SPP:-256}-seed${MASK_SEED:-9003}.pfm
  [ -f "$mask_ref" ] || { "$bin" --headless --quiet --scene cat --target-spp "${MASK_SPP:-256}" \
    --seed "${MASK_SEED:-9003}" --out-float "$mask_ref.part.pfm" >/dev/null && mv "$mask_ref.part.pfm" "$mask_ref"; }
  for sc in cat glass-cat; do
    sc_spp=$ref_spp
    [ "$sc" = glass-cat ] && sc_spp=${GLASS_REF_SPP:-$ref_spp}
    reference "$sc" "$sc_spp"
    imgs=()
    for n in "${counts[@]}"; do
      # The denoiser needs two half images: at 1 spp the raw image stands in
      # for the copy (its row reads 1.00, marked "no copy").
      if [ "$n" -lt 2 ]; then
        "$bin" --headless --quiet --scene "$sc" --target-spp "$n" --seed 1 --out-float "$work/$sc-$n-raw.pfm" >/dev/null
        cp "$work/$sc-$n-raw.pfm" "$work/$sc-$n-denoised.pfm"
      else
        "$bin" --headless --quiet --scene "$sc" --target-spp "$n" --seed 1 --out-float "$work/$sc-$n-raw.pfm" \
          --out-denoised "$work/$sc-$n-denoised.pfm" --denoiser "$filter" >/dev/null
      fi
      imgs+=("$work/$sc-$n-raw.pfm" "$work/$sc-$n-denoised.pfm")
    done
    echo "--- $sc, $filter filter, against 2 x $sc_spp spp (seeds $ref_a, $ref_b): MSE per place (display white)"
    python3 "$here/error_by_region.py" --places "$mask_ref" \
      "$refs/$sc-$sc_spp-seed$ref_a.pfm" "$refs/$sc-$sc_spp-seed$ref_b.pfm" "${imgs[@]}" \
      --json "$work/$sc.json" ${PICTURES:+--masks "$work/places.png"} | sed "s|$work/||g"
    # Denoised over raw per place, one row per count (the pairs in order).
    python3 - "$work/$sc.json" "${counts[*]}" "$sc" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
names = list(out["images"][0]["mse"])
print(f"| {sys.argv[3]} denoised/raw, spp | " + " | ".join(names) + " | whiskers' red kept, raw / denoised |")
print("|---|" + "---|" * (len(names) + 1))
for n, raw, dn in zip(sys.argv[2].split(), out["images"][0::2], out["images"][1::2]):
    if int(n) < 2:
        print(f"| {n} (no copy: the denoiser needs 2 spp) | " + " | ".join("-" for k in names)
              + f" | {raw['whiskers_red_kept']:.2f} / - |")
        continue
    print(f"| {n} | " + " | ".join(f"{dn['mse'][k] / raw['mse'][k]:.2f}" for k in names)
          + f" | {raw['whiskers_red_kept']:.2f} / {dn['whiskers_red_kept']:.2f} |")
PY
  done
  if [ -n "${PICTURES:-}" ]; then
    mkdir -p "$PICTURES"
    crop=${CROP:-288,150,192,192}
    gain=${GAIN:-4}
    python3 "$here/pfm.py" mean "$refs/cat-$ref_spp-seed$ref_a.pfm" "$refs/cat-$ref_spp-seed$ref_b.pfm" "$work/ref.pfm"
    python3 "$here/pfm.py" png "$work/ref.pfm" "$PICTURES/cat-reference.png" --crop "$crop"
    cp "$work/places.png" "$PICTURES/cat-places.png"
    for n in "${counts[@]}"; do
      case " 4 16 64 " in *" $n "*) ;; *) continue ;; esac
      for kind in raw denoised; do
        python3 "$here/pfm.py" png "$work/cat-$n-$kind.pfm" "$PICTURES/cat-$n-$kind.png" --crop "$crop"
        python3 "$here/pfm.py" png "$work/cat-$n-$kind.pfm" "$PICTURES/cat-$n-$kind-diff.png" \
          "$work/ref.pfm" "$gain" --crop "$crop"
      done
    done
    echo "pictures: $PICTURES ($(du -ch "$PICTURES"/*.png | tail -1 | cut -f1))"
  fi
  exit 0
fi
reference "$scene"
table="| filter, spp | 1 px | 2 px | 4 px | 8 px | 16 px |
|---|---|---|---|---|---|"
for filter in quality fast; do
  for n in "${counts[@]}"; do
    echo "--- $scene, $n spp, $filter filter"
    "$bin" --headless --quiet --scene "$scene" --target-spp "$n" --seed 1 --out-float "$work/raw.pfm" \
      --out-denoised "$work/dn.pfm" --denoiser "$filter" --stats "$work/s.json" | head -1
    python3 "$here/denoise_error.py" "$refs/$scene-$ref_spp-seed$ref_a.pfm" \
      "$refs/$scene-$ref_spp-seed$ref_b.pfm" "$work/raw.pfm" "$work/dn.pfm" "$work/s.json" | tee "$work/e.txt"
    # The denoised/raw column, one row of the summary.
    table+=$'\n'"| $filter, $n |$(awk 'NR > 1 { printf " %.2f |", $5 }' "$work/e.txt")"
  done
done
echo "--- denoised/raw error, $scene against 2 x $ref_spp spp"
echo "$table"
