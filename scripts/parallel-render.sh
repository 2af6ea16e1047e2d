#!/usr/bin/env bash
# Renders SCENE at SPP samples per pixel in TASKS sample ranges with GNU
# parallel, then merges them: the plain-shell sibling of slurm-render.sh.
#
#   scripts/parallel-render.sh SCENE SPP TASKS [OUT.exr]
#
# Part i holds samples [i*SPP/TASKS, (i+1)*SPP/TASKS), rendered as one pass
# into OUT.parts/part-i.exr; the merge writes OUT.exr and OUT.png, equal bit
# for bit to `whisker --headless --samples 0:SPP --spp SPP/TASKS` (when TASKS
# divides SPP; docs/SHARDS.md). A part already on disk is kept, so a rerun
# after an interruption renders only what is missing.
#
# Environment:
#   WHISKER        the whisker binary (default: build/whisker here)
#   WHISKER_ARGS   more options for every part, e.g. "--indirect on --seed 3"
#   JOBS           parts at once (default 1: each part uses every core)
#   PARALLEL_ARGS  more options for parallel, e.g. "--sshloginfile nodes.txt"
#                  (other machines need the binary and the scene at the same
#                  paths and a shared OUT folder)
set -euo pipefail

usage() { echo "usage: $0 SCENE SPP TASKS [OUT.exr]" >&2; exit 2; }
[ $# -ge 3 ] && [ $# -le 4 ] || usage
scene=$1 spp=$2 tasks=$3
out=${4:-$PWD/$(basename "${scene%.json}")-$spp.exr}
[[ $spp =~ ^[1-9][0-9]*$ && $tasks =~ ^[1-9][0-9]*$ ]] || { echo "$0: SPP and TASKS must be positive integers" >&2; exit 2; }
[ "$tasks" -le "$spp" ] || { echo "$0: TASKS ($tasks) must be at most SPP ($spp)" >&2; exit 2; }
[[ $out == *.exr ]] || { echo "$0: OUT must end in .exr, got $out" >&2; exit 2; }
command -v parallel >/dev/null || { echo "$0: GNU parallel not found (apt-get install parallel)" >&2; exit 2; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
whisker=${WHISKER:-$root/build/whisker}
[ -x "$whisker" ] || { echo "$0: $whisker is not an executable (set WHISKER)" >&2; exit 2; }
out=$(realpath -m "$out")
[[ $scene == */* || $scene == *.json ]] && scene=$(realpath "$scene")
parts=${out%.exr}.parts
mkdir -p "$parts"
jobs=${JOBS:-1}
threads=$(( $(nproc) / jobs )); [ "$threads" -ge 1 ] || threads=1
read -r -a parallel_args <<<"${PARALLEL_ARGS:-}"

files=()
for ((i = 0; i < tasks; ++i)); do files+=("$parts/part-$i.exr"); done
# One command line per missing part; parallel runs them JOBS at a time.
for ((i = 0; i < tasks; ++i)); do
  begin=$(( i * spp / tasks )) end=$(( (i + 1) * spp / tasks ))
  [ -f "$parts/part-$i.exr" ] && continue
  printf '%q ' "$whisker" --headless --quiet --scene "$scene" ${WHISKER_ARGS:-} --threads "$threads" \
    --samples "$begin:$end" --spp "$(( end - begin ))" --out-sum "$parts/part-$i.exr"
  printf '\n'
done | parallel --will-cite --halt now,fail=1 -j "$jobs" "${parallel_args[@]}"
"$whisker" merge "${files[@]}" --out "$out" --out "${out%.exr}.png"
