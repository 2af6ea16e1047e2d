#!/usr/bin/env bash
# The cat target at every scale, measured side by side at full size (512x512,
# fig 8 settings): how long Whisker needs to reach the error that the report's
# own program has at 1024 samples per pixel, at pixel scale and after
# box-filtering both images by 2, 4, 8 and 16 px, against how long that
# program takes. Both programs run in this script, interleaved (report,
# Whisker's estimators, report, ...). The headline is the worst scale: an
# estimator that moves error from fine grain into blotches gains at pixel
# scale and loses at the blotches' scale, and a person sees the blotches.
#
#   bench/cat_target.sh            # ~11 minutes on the 2-core machine; quiet machine please
#
# Error without a reference image: two renders with independent seeds a and
# b of an unbiased estimator have E|a - b|^2 = MSE_a + MSE_b, so the MSE of
# one render is half the MSE between the two, at each scale (whisker-compare
# box-filters both images by k before the MSE, in units of the report's
# display white, 255^2.2).
#
# 1. The report's program (built from its source, its two bugs mended so that
#    it converges to Whisker's image; bench/report_program.sh) at REPORT_SPP
#    with two seeds (and, untimed, the pairs of CHECK_SEEDS: the target is the
#    mean of all pairs'). Plain Monte Carlo with independent pixels, so its MSE at
#    1024 spp is MSE(REPORT_SPP) * REPORT_SPP / 1024 at every scale. Its time
#    for 1024 spp: measured directly with REPORT_FULL=1 (~8 minutes),
#    otherwise from its times at REPORT_SMALL and REPORT_SPP samples,
#    t(1024) = t(S) + (1024 - S) x the time per sample between the two.
# 2. Each of Whisker's estimators in CONFIGS at each of its sample counts,
#    two seeds: time (whole process, wall, mean of the seeds) and MSE per scale.
# 3. Per estimator and scale, the samples per pixel that reach the target
#    (log-log interpolation of MSE against spp between the measured counts,
#    extrapolated along the measured slope, between -0.5 and -2) and their
#    time (the line through the measured times), against the report program's.
# 4. The check render (the headline): the defaults rendered at the count
#    step 3 gives for their worst scale, and at more samples until the
#    images reach the target at every scale (the mean MSE of four pairs of
#    seeds); that count's time (the line of step 3) against the report
#    program's.
#
# The denoised copies (DENOISE=1): CONFIGS become the defaults raw and with
# --out-denoised by each filter (an estimator whose flags hold --denoiser is
# timed render + filter in one process, and its image is the denoised copy).
# A denoised copy is biased, so the two seeds' difference no longer gives its
# error: every estimator (raw too) is measured against a converged reference
# instead, the mean of two renders of REF_SPP samples (REF_SEEDS, cached in
# $BUILD/references/), its own noise (a quarter of the MSE between the two)
# subtracted, bias included (time_to_error.py reference). Then, per filter,
# the denoised MSE over the raw at equal samples, the denoised headline
# against the 200x goal, and the denoiser's own estimate against the true
# error (bench/denoise_error.py on a render of ESTIMATE_SPP with --sampler
# independent, which the estimate needs). The check render stays the raw
# defaults'.
#
#   DENOISE=1 CHECK_SEEDS="303 404" bench/cat_target.sh   # ~10 minutes, the references apart
#
# CONFIGS: estimators separated by ';', each "name|whisker flags|spp counts".
# The first is the defaults (the scene's settings). The script exits 1 when
# the defaults reach the target later than another of them at any scale by
# more than TOLERANCE (a fraction, default 0.1: all are timed on a shared
# machine).
#
# Knobs: WHISKER_BUILD, REPORT_SPP (16), REPORT_SMALL (2), REPORT_FULL (0),
# REPORT_PROGRAM_DIR, CONFIGS, SEEDS ("101 202": exactly two), CHECK_SEEDS
# (more pairs for the target and the check render, "303 404 505 606 707
# 808"; empty: SEEDS alone), THREADS (2),
# SCALES ("1 2 4 8 16"), TOLERANCE, CAT_OUT (output dir, default
# $BUILD/cat-target; every image and JSON stays there), DENOISE (0),
# REF_SPP (512), REF_SEEDS ("9001 9002": two, none of SEEDS or CHECK_SEEDS),
# ESTIMATE_SPP (16). The FAIL rule below compares raw estimators only.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$ROOT/bench/report_program.sh"
BUILD=${WHISKER_BUILD:-$ROOT/build}
REPORT_SPP=${REPORT_SPP:-16}
REPORT_SMALL=${REPORT_SMALL:-2}
REPORT_FULL=${REPORT_FULL:-0}
DENOISE=${DENOISE:-0}
if [ "$DENOISE" = 1 ]; then
  CONFIGS=${CONFIGS:-"defaults||16 32;fast|--denoiser fast|8 16 32;quality|--denoiser quality|8 16 32"}
else
  CONFIGS=${CONFIGS:-"defaults||16 32;no-connect|--connect off|24 48"}
fi
REF_SPP=${REF_SPP:-512}
read -r REF_A REF_B <<<"${REF_SEEDS:-9001 9002}"
ESTIMATE_SPP=${ESTIMATE_SPP:-16}
read -r SEED_A SEED_B <<<"${SEEDS:-101 202}"
CHECK_SEEDS=${CHECK_SEEDS-303 404 505 606 707 808}
read -r -a EXTRA <<<"$CHECK_SEEDS"
[ $((${#EXTRA[@]} % 2)) -eq 0 ] || { echo "CHECK_SEEDS: pairs of seeds, got '$CHECK_SEEDS'" >&2; exit 2; }
THREADS=${THREADS:-2}
SCALES=${SCALES:-"1 2 4 8 16"}
TOLERANCE=${TOLERANCE:-0.1}
OUT=${CAT_OUT:-$BUILD/cat-target}
mkdir -p "$OUT" && OUT=$(cd "$OUT" && pwd)  # absolute: the report program runs from its own folder

cmake --build "$BUILD" -j 2 --target whisker whisker-compare >/dev/null
mkdir -p "$OUT/bin"
# Private copies: a rebuild during the run must not swap the renderer.
cp "$BUILD/whisker" "$OUT/bin/whisker"
cp "$BUILD/bench/convergence/whisker-compare" "$OUT/bin/whisker-compare"
WHISKER=$OUT/bin/whisker
COMPARE=$OUT/bin/whisker-compare
report_program_build "$OUT"

seconds_since() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.3f}')" "$1" "$(date +%s.%N)"; }

# render TAG SPP SEED FLAGS... -> prints the wall seconds of the whole process.
# Flags with --denoiser: TAG-SEED.pfm is the denoised copy, TAG-SEED-raw.pfm
# the raw image of the same process.
render() {
  local tag=$1 spp=$2 seed=$3 t0 outs
  shift 3
  outs=(--out-float "$OUT/$tag-$seed.pfm")
  [[ " $* " == *" --denoiser "* ]] && outs=(--out-float "$OUT/$tag-$seed-raw.pfm" --out-denoised "$OUT/$tag-$seed.pfm")
  t0=$(date +%s.%N)
  # shellcheck disable=SC2068
  "$WHISKER" --headless --scene cat --frames 1 --spp "$spp" --seed "$seed" \
    --threads "$THREADS" --quiet "${outs[@]}" $@ >/dev/null
  seconds_since "$t0"
}

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
scales_csv=$(tr ' ' ',' <<<"$SCALES")

# The converged reference (DENOISE=1): rendered once, cached, not timed.
if [ "$DENOISE" = 1 ]; then
  mkdir -p "$BUILD/references"
  for seed in "$REF_A" "$REF_B"; do
    ref=$BUILD/references/cat-$REF_SPP-seed$seed.pfm
    [ -f "$ref" ] || { "$WHISKER" --headless --quiet --scene cat --target-spp "$REF_SPP" --seed "$seed" \
      --threads "$THREADS" --out-float "$ref.part.pfm" >/dev/null && mv "$ref.part.pfm" "$ref"; }
  done
  REF1=$BUILD/references/cat-$REF_SPP-seed$REF_A.pfm
  REF2=$BUILD/references/cat-$REF_SPP-seed$REF_B.pfm
  python3 "$ROOT/bench/pfm.py" mean "$REF1" "$REF2" "$OUT/reference.pfm"
  "$COMPARE" "$REF1" "$REF2" --scales "$scales_csv" --json "$OUT/reference-pair.json" >/dev/null
  echo "reference: the mean of 2 x $REF_SPP spp (seeds $REF_A, $REF_B), its own MSE subtracted"
fi

IFS=';' read -r -a CONFIG_LIST <<<"$CONFIGS"
TIMES=$OUT/times.txt
: >"$TIMES"
# Interleaved: for each seed, the report's program, then every estimator at
# every count, then the report's program at its small count.
for seed in "$SEED_A" "$SEED_B"; do
  echo "report $REPORT_SPP $seed $(report_program_run "$REPORT_CAT" "$REPORT_SPP" "$seed" "$OUT/report-$REPORT_SPP-$seed.pfm")" >>"$TIMES"
  for config in "${CONFIG_LIST[@]}"; do
    IFS='|' read -r name flags counts <<<"$config"
    for spp in $counts; do
      echo "$name $spp $seed $(render "$name-$spp" "$spp" "$seed" "$flags")" >>"$TIMES"
    done
  done
  echo "report $REPORT_SMALL $seed $(report_program_run "$REPORT_CAT" "$REPORT_SMALL" "$seed" "$OUT/report-$REPORT_SMALL-$seed.pfm")" >>"$TIMES"
done
# The report program's further pairs of seeds (CHECK_SEEDS), for its
# target: one pair's 16-px MSE spreads by several per cent. Not timed (its
# times above are).
for seed in "${EXTRA[@]}"; do
  report_program_run "$REPORT_CAT" "$REPORT_SPP" "$seed" "$OUT/report-$REPORT_SPP-$seed.pfm" >/dev/null
done
# compare_pairs TAG: TAG-SEED.pfm of the pairs of CHECK_SEEDS compared into
# TAG-p2.json, TAG-p3.json, ... (time_to_error.py takes the mean with
# TAG.json, the pair of SEEDS); stale ones of an earlier run removed.
compare_pairs() {
  local tag=$1 k
  rm -f "$OUT/$tag"-p[0-9]*.json
  for ((k = 0; k < ${#EXTRA[@]}; k += 2)); do
    "$COMPARE" "$OUT/$tag-${EXTRA[k]}.pfm" "$OUT/$tag-${EXTRA[k + 1]}.pfm" \
      --scales "$scales_csv" --json "$OUT/$tag-p$((k / 2 + 2)).json" >/dev/null
  done
}
if [ "$REPORT_FULL" = 1 ]; then
  echo "report 1024 $SEED_A $(report_program_run "$REPORT_CAT" 1024 "$SEED_A" "$OUT/report-1024-$SEED_A.pfm")" >>"$TIMES"
fi

# The MSE of one image, per scale, for every (estimator, count): from the
# two seeds' difference, or (DENOISE=1) against the reference.
"$COMPARE" "$OUT/report-$REPORT_SPP-$SEED_A.pfm" "$OUT/report-$REPORT_SPP-$SEED_B.pfm" \
  --scales "$scales_csv" --json "$OUT/report-$REPORT_SPP.json" >/dev/null
compare_pairs "report-$REPORT_SPP"
for config in "${CONFIG_LIST[@]}"; do
  IFS='|' read -r name flags counts <<<"$config"
  for spp in $counts; do
    if [ "$DENOISE" = 1 ]; then
      for seed in "$SEED_A" "$SEED_B"; do
        "$COMPARE" "$OUT/$name-$spp-$seed.pfm" "$OUT/reference.pfm" \
          --scales "$scales_csv" --json "$OUT/$name-$spp-$seed.ref.json" >/dev/null
      done
      python3 "$ROOT/bench/time_to_error.py" reference "$OUT/$name-$spp.json" "$OUT/reference-pair.json" \
        "$OUT/$name-$spp-$SEED_A.ref.json" "$OUT/$name-$spp-$SEED_B.ref.json"
    else
      "$COMPARE" "$OUT/$name-$spp-$SEED_A.pfm" "$OUT/$name-$spp-$SEED_B.pfm" \
        --scales "$scales_csv" --json "$OUT/$name-$spp.json" >/dev/null
    fi
  done
done
status=0
python3 "$ROOT/bench/time_to_error.py" "$OUT" "$TIMES" "$CONFIGS" "$SCALES" \
  "$REPORT_SPP" "$REPORT_SMALL" "$REPORT_FULL" "$TOLERANCE" || status=$?

# The denoiser's own estimate against the true error, per filter (the
# estimate needs independent halves: --sampler independent).
if [ "$DENOISE" = 1 ]; then
  for filter in fast quality; do
    echo "--- the $filter filter's estimate, $ESTIMATE_SPP spp, --sampler independent, seed $SEED_A"
    "$WHISKER" --headless --scene cat --frames 1 --spp "$ESTIMATE_SPP" --seed "$SEED_A" --threads "$THREADS" \
      --quiet --sampler independent --out-float "$OUT/estimate-$filter-raw.pfm" \
      --out-denoised "$OUT/estimate-$filter.pfm" --denoiser "$filter" --stats "$OUT/estimate-$filter.json" >/dev/null
    python3 "$ROOT/bench/denoise_error.py" "$REF1" "$REF2" "$OUT/estimate-$filter-raw.pfm" \
      "$OUT/estimate-$filter.pfm" "$OUT/estimate-$filter.json"
  done
fi

# The check render: the interpolated count is only an estimate (the Sobol
# points are best stratified at powers of two, so 28 spp lie above the line
# through 16 and 32), so the defaults are rendered at it, rounded up, with
# every pair of seeds, and at more samples until the images reach the
# target at every scale (judged on the mean MSE of the pairs, SEEDS and
# CHECK_SEEDS: an MSE from the 1024 blocks of 16 px of one pair spreads by
# about 5 %, and the worst of five noisy scales reads high). That count is
# the headline, with its time from the line
# through the timings of step 2, which ran interleaved with the report
# program's (the check renders' own times are printed too).
defaults_flags=$(IFS='|' read -r _ f _ <<<"${CONFIG_LIST[0]}"; echo "$f")
check_spp=$(python3 -c "import json, math, sys; print(math.ceil(json.load(open(sys.argv[1]))['need']))" "$OUT/check.json")
for _ in 1 2 3 4 5 6; do
  ta=$(render "check-$check_spp" "$check_spp" "$SEED_A" "$defaults_flags")
  tb=$(render "check-$check_spp" "$check_spp" "$SEED_B" "$defaults_flags")
  "$COMPARE" "$OUT/check-$check_spp-$SEED_A.pfm" "$OUT/check-$check_spp-$SEED_B.pfm" \
    --scales "$scales_csv" --json "$OUT/check-$check_spp.json" >/dev/null
  for seed in "${EXTRA[@]}"; do render "check-$check_spp" "$check_spp" "$seed" "$defaults_flags" >/dev/null; done
  compare_pairs "check-$check_spp"
  secs=$(python3 -c "import sys; print((float(sys.argv[1]) + float(sys.argv[2])) / 2)" "$ta" "$tb")
  verdict=$(python3 "$ROOT/bench/time_to_error.py" check "$OUT" "$check_spp" "$secs") && { echo "$verdict"; break; }
  echo "$verdict" | sed '$d'
  check_spp=$(echo "$verdict" | tail -1)
done

# The noise pictures and the time-normalised error spectra, each estimator at
# its largest count and the report's program at REPORT_SPP (Debian's
# python3-numpy, python3-pil and gnuplot; installed when missing and allowed).
spectrum_tools() {
  /usr/bin/python3 -c 'import numpy, PIL' 2>/dev/null && command -v gnuplot >/dev/null && return 0
  local sudo=()
  [ "$(id -u)" -ne 0 ] && { command -v sudo >/dev/null || return 1; sudo=(sudo -n); }
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -q --no-install-recommends \
    python3-numpy python3-pil gnuplot-nox >/dev/null 2>&1
}
if spectrum_tools; then
  mean_time() { awk -v n="$1" -v s="$2" '$1 == n && $2 == s {t += $4; c++} END {printf "%.3f", t / c}' "$TIMES"; }
  curves=("report:$OUT/report-$REPORT_SPP-$SEED_A.pfm:$OUT/report-$REPORT_SPP-$SEED_B.pfm:$(mean_time report "$REPORT_SPP")")
  for config in "${CONFIG_LIST[@]}"; do
    IFS='|' read -r name flags counts <<<"$config"
    last=${counts##* }
    curves+=("$name:$OUT/$name-$last-$SEED_A.pfm:$OUT/$name-$last-$SEED_B.pfm:$(mean_time "$name" "$last")")
  done
  /usr/bin/python3 "$ROOT/bench/error_spectrum.py" "$OUT/cat" "${curves[@]}"
  echo "noise pictures and spectrum: $OUT/cat-noise-*.png, $OUT/cat-spectrum.png"
else
  echo "spectrum skipped: needs python3-numpy, python3-pil and gnuplot (Debian packages)"
fi
exit "$status"
