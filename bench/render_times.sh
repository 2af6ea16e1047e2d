#!/usr/bin/env bash
# Render time of the report's scenes at the report's settings, headless, all
# threads: median of R runs each. Not part of the test run.
#   bench/render_times.sh [runs=3]       (build/ must be built)
# Prints a markdown table. The cat at 1024 spp (fig 8) runs with each
# sampler: the report's independent random numbers (`--sampler independent`,
# the report's settings in full: the same estimator and the same error per
# sample as the report's program) and Whisker's default Sobol points (half
# that error at equal samples; docs/PERFORMANCE.md), each followed by the
# report's own program (bench/report_program.sh), in REPORT_RUNS (3) rounds;
# the medians of the rounds. The program's time is measured at 1024 spp with
# REPORT_FULL=1 (~8 minutes a round), else from its times at REPORT_SMALL (4)
# and REPORT_SPP (64) samples per pixel, t(1024) = t(S) + (1024 - S) x the
# time per sample between the two medians (the extrapolation multiplies a
# timing's noise by 16: one run of each moved it by up to a fifth from run
# to run).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/report_program.sh
runs=${1:-3}
REPORT_SPP=${REPORT_SPP:-64}
REPORT_SMALL=${REPORT_SMALL:-4}
REPORT_RUNS=${REPORT_RUNS:-3}
THREADS=${THREADS:-$(nproc)}
bin=${WHISKER_BUILD:-build}/whisker
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

# One render, one path per sample and pixel (--split 1), as
# the report's program: the figures compare with its times per sample.
# Prints its seconds (from --stats, left in JSON).
render_once() {  # json, whisker options...
  local json=$1
  shift
  "$bin" --headless --quiet --split 1 --connect off "$@" --stats "$json" >/dev/null
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["seconds"])' "$json"
}

print_row() {  # name, json of one run, options, seconds of each run...
  local name=$1 json=$2 args=$3
  shift 3
  local med
  med=$(printf '%s\n' "$@" | median)
  python3 - "$name" "$med" "$#" "$json" "$args" <<'PY'
import json, sys
name, med, n, path, args = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
s = json.load(open(path))
px = s["width"] * s["height"] * s["spp"]
print(f"| {name} | {s['spp']} | {med:.3f} | {px / med / 1e6:.2f} | {s['rays'] / s['seconds'] / 1e6:.2f} | {n} | `{args}` |")
PY
}

row() {  # name, runs, whisker options...
  local name=$1 n=$2
  shift 2
  local secs=() k
  for ((k = 0; k < n; k++)); do secs+=("$(render_once "$out/s.json" "$@")"); done
  print_row "$name" "$out/s.json" "$*" "${secs[@]}"
}

echo "| scene | spp | seconds (median) | Mpaths/s | Mrays/s | runs | options |"
echo "|---|---|---|---|---|---|---|"
row diffuse-ball "$runs" --scene diffuse-ball --frames 1
row three-balls "$runs" --scene three-balls --frames 1
row three-balls-fresnel "$runs" --scene three-balls-fresnel --frames 64 --spp 16
row indirect "$runs" --scene indirect --frames 2 --spp 16
row antialiased-ball "$runs" --scene antialiased-ball --frames 2 --spp 16
row cat-brute 1 --scene cat-brute --frames 1
# Fig 8: REPORT_RUNS rounds, each Whisker with both samplers and then the
# report's program, so that all three see the same moments of a shared
# machine; medians of the rounds.
report_program_build "$out" >/dev/null
fig8=(--scene cat --frames 64 --spp 16)
f8_ind=() f8_sobol=() small=() big=() full=()
for ((k = 0; k < REPORT_RUNS; k++)); do
  f8_ind+=("$(render_once "$out/ind.json" "${fig8[@]}" --sampler independent)")
  f8_sobol+=("$(render_once "$out/sobol.json" "${fig8[@]}" --sampler sobol)")
  if [ "${REPORT_FULL:-0}" = 1 ]; then
    full+=("$(report_program_run "$REPORT_CAT" 1024 1 "$out/r.pfm")")
  else
    small+=("$(report_program_run "$REPORT_CAT" "$REPORT_SMALL" 1 "$out/r.pfm")")
    big+=("$(report_program_run "$REPORT_CAT" "$REPORT_SPP" 1 "$out/r.pfm")")
  fi
done
print_row "cat (fig 8)" "$out/ind.json" "${fig8[*]} --sampler independent" "${f8_ind[@]}"
print_row "cat (fig 8, Sobol)" "$out/sobol.json" "${fig8[*]} --sampler sobol" "${f8_sobol[@]}"
if [ "${REPORT_FULL:-0}" = 1 ]; then
  rt=$(printf '%s\n' "${full[@]}" | median)
  how="the median of its runs at 1024 spp (${full[*]} s)"
else
  t_small=$(printf '%s\n' "${small[@]}" | median)
  t_spp=$(printf '%s\n' "${big[@]}" | median)
  rt=$(python3 -c "print(f'{$t_spp + (1024 - $REPORT_SPP) * ($t_spp - $t_small) / ($REPORT_SPP - $REPORT_SMALL):.1f}')")
  how="from the medians of its times at $REPORT_SMALL spp (${small[*]} s) and $REPORT_SPP spp (${big[*]} s)"
fi
echo
echo "the report's program (bugs mended), fig 8 at 1024 spp, $THREADS threads: $rt s ($how)"
