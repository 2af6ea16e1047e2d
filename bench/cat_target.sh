#!/usr/bin/env bash
# The cat target, measured directly at full size (512x512, fig 8 settings) and
# side by side: how long Whisker needs to reach the error that the report's own
# program has at 1024 samples per pixel, against how long that program takes.
# Both programs run in this script, interleaved (report, Whisker, report, ...).
#
#   bench/cat_target.sh            # ~4 minutes on the 2-core machine
#
# Error without a reference image: two renders with independent seeds a and
# b of an unbiased estimator have E|a - b|^2 = MSE_a + MSE_b, so the MSE of
# one render is half the MSE between the two (whisker-compare, same white
# point as the convergence study).
#
# 1. The report's program (built from its source, its two bugs mended so that it
#    converges to Whisker's image; bench/report_program.sh) at REPORT_SPP with
#    two seeds: plain Monte Carlo, so its MSE at 1024 spp is
#    MSE(REPORT_SPP) * REPORT_SPP / 1024. Its time for 1024 spp: measured
#    directly with REPORT_FULL=1 (~10 minutes), otherwise from its times at
#    REPORT_SMALL and REPORT_SPP samples, t(1024) = t(S) + (1024 - S) x the
#    time per sample between the two (the load and BVH build counted once).
# 2. Whisker's defaults (or BEST_FLAGS) at each count in BEST_SPP, two seeds:
#    time (whole process, wall) and MSE.
# 3. The first count whose MSE is at or below the target, and its time
#    against the report program's.
#
# Knobs: WHISKER_BUILD, REPORT_SPP (16), REPORT_SMALL (2), REPORT_FULL (0),
# REPORT_PROGRAM_DIR, BEST_SPP ("6 7 8 10 16"), BEST_FLAGS (""), SEEDS ("101 202":
# exactly two), THREADS (2), CAT_OUT (output dir, default $BUILD/cat-target).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$ROOT/bench/report_program.sh"
BUILD=${WHISKER_BUILD:-$ROOT/build}
REPORT_SPP=${REPORT_SPP:-16}
REPORT_SMALL=${REPORT_SMALL:-2}
REPORT_FULL=${REPORT_FULL:-0}
BEST_SPP=${BEST_SPP:-"6 7 8 10 16"}
read -r -a BEST_FLAGS <<<"${BEST_FLAGS:-}"
read -r SEED_A SEED_B <<<"${SEEDS:-101 202}"
THREADS=${THREADS:-2}
OUT=${CAT_OUT:-$BUILD/cat-target}

cmake --build "$BUILD" -j 2 --target whisker whisker-compare >/dev/null
mkdir -p "$OUT/bin"
# Private copies: a rebuild during the run must not swap the renderer.
cp "$BUILD/whisker" "$OUT/bin/whisker"
cp "$BUILD/bench/convergence/whisker-compare" "$OUT/bin/whisker-compare"
WHISKER=$OUT/bin/whisker
COMPARE=$OUT/bin/whisker-compare
report_program_build "$OUT"

# render TAG SPP SEED FLAGS... -> prints the wall seconds of the whole process
render() {
  local tag=$1 spp=$2 seed=$3
  shift 3
  local t0 t1
  t0=$(date +%s.%N)
  "$WHISKER" --headless --scene cat --frames 1 --spp "$spp" --seed "$seed" \
    --threads "$THREADS" --quiet --out-float "$OUT/$tag-$seed.pfm" "$@" >/dev/null
  t1=$(date +%s.%N)
  python3 -c "print(f'{$t1 - $t0:.3f}')"
}

# mse TAG -> half the MSE between the two seeds' images
mse() {
  "$COMPARE" "$OUT/$1-$SEED_A.pfm" "$OUT/$1-$SEED_B.pfm" --json "$OUT/$1.json" >/dev/null
  python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['mse'] / 2)" "$OUT/$1.json"
}
mean2() { python3 -c "print(($1 + $2) / 2)"; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"

# Interleaved: for each seed, the report's program, then Whisker at every count.
declare -A WT RT RS
for seed in "$SEED_A" "$SEED_B"; do
  RT[$seed]=$(report_program_run "$REPORT_CAT" "$REPORT_SPP" "$seed" "$OUT/report-$seed.pfm")
  for spp in $BEST_SPP; do
    WT[$spp-$seed]=$(render "best-$spp" "$spp" "$seed" "${BEST_FLAGS[@]}")
  done
  RS[$seed]=$(report_program_run "$REPORT_CAT" "$REPORT_SMALL" "$seed" "$OUT/report-small-$seed.pfm")
done
rmse=$(mse report)
target=$(python3 -c "print($rmse * $REPORT_SPP / 1024)")
t_spp=$(mean2 "${RT[$SEED_A]}" "${RT[$SEED_B]}")
t_small=$(mean2 "${RS[$SEED_A]}" "${RS[$SEED_B]}")
if [ "$REPORT_FULL" = 1 ]; then
  report_1024=$(report_program_run "$REPORT_CAT" 1024 "$SEED_A" "$OUT/report-1024.pfm")
  how="measured at 1024 spp"
else
  report_1024=$(python3 -c "print($t_spp + (1024 - $REPORT_SPP) * ($t_spp - $t_small) / ($REPORT_SPP - $REPORT_SMALL))")
  how="from its times at $REPORT_SMALL spp ($t_small s) and $REPORT_SPP spp ($t_spp s)"
fi
echo "report's program at $REPORT_SPP spp: MSE $rmse; its 1024-spp time $report_1024 s ($how)"
echo "target: the report program's MSE at 1024 spp = $target"
echo
echo "| spp | seconds (wall, mean of 2) | MSE of one image | reaches target | report program's 1024-spp time / seconds |"
echo "|---|---|---|---|---|"
rows=()
for spp in $BEST_SPP; do
  m=$(mse "best-$spp")
  w=$(mean2 "${WT[$spp-$SEED_A]}" "${WT[$spp-$SEED_B]}")
  rows+=("$spp $w $m")
  python3 -c "
s, w, m, t, r = $spp, $w, $m, $target, $report_1024
print(f'| {s} | {w:.2f} | {m:.3e} | {\"yes\" if m <= t else \"no\"} | {r / w:.1f}x |')"
done
echo
printf '%s\n' "${rows[@]}" | python3 -c "
import sys
t, r = $target, $report_1024
rows = [tuple(map(float, l.split())) for l in sys.stdin if l.strip()]
ok = [x for x in rows if x[2] <= t]
if ok:
    s, w, m = min(ok, key=lambda x: x[1])
    print(f'first count at or below the target: {int(s)} spp, {w:.2f} s -> {r / w:.1f}x less than the report program ({r:.0f} s; 100x needs <= {r / 100:.1f} s)')
else:
    print('no measured count reaches the target')
"
