#!/usr/bin/env bash
# Two whisker binaries timed on the same render, interleaved (A, B, A, B, ...)
# so that both see the same moments of a shared machine; prints each one's
# median wall time and the median of the per-pair ratios B / A, and whether
# their images are the same bit for bit.
#
#   bench/ab_time.sh OLD_WHISKER NEW_WHISKER [RUNS] [-- whisker arguments]
#
# e.g. the binary of another commit against this build, on the cat:
#   git worktree add /tmp/old HEAD~5 && cmake -S /tmp/old -B /tmp/old/build \
#     -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/old/build -j2 --target whisker
#   bench/ab_time.sh /tmp/old/build/whisker build/whisker 7 -- --scene cat --spp 4
# Default arguments: --scene cat --frames 1 --spp 4; RUNS defaults to 7.
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,13p "$0"; exit 2; }
A=$1 B=$2
shift 2
RUNS=7
if [ $# -gt 0 ] && [ "$1" != -- ]; then RUNS=$1; shift; fi
[ "${1:-}" = -- ] && shift
ARGS=("$@")
[ ${#ARGS[@]} -gt 0 ] || ARGS=(--scene cat --spp 4)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

run() {  # binary tag k -> wall seconds
  local t0
  t0=$(date +%s.%N)
  "$1" --headless --frames 1 --quiet "${ARGS[@]}" --out-float "$OUT/$2-$3.pfm" >/dev/null
  python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.4f}')" "$t0" "$(date +%s.%N)"
}

ta=() tb=()
for ((k = 1; k <= RUNS; k++)); do
  ta+=("$(run "$A" a "$k")")
  tb+=("$(run "$B" b "$k")")
done
same=yes
cmp -s "$OUT/a-1.pfm" "$OUT/b-1.pfm" || same=no
python3 - "$same" "${ta[*]}" "${tb[*]}" <<'PY'
import statistics, sys
same, ta, tb = sys.argv[1], list(map(float, sys.argv[2].split())), list(map(float, sys.argv[3].split()))
ratios = [b / a for a, b in zip(ta, tb)]
print(f"A median {statistics.median(ta):.3f} s, B median {statistics.median(tb):.3f} s, "
      f"B/A median of {len(ratios)} pairs {statistics.median(ratios):.3f} "
      f"({', '.join(f'{r:.3f}' for r in ratios)}); images bit for bit the same: {same}")
PY
