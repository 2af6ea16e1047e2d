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

source "$(dirname "${BASH_SOURCE[0]}")/render_parts_args.sh"
render_parts_args parallel "GNU parallel not found (apt-get install parallel)" "$@"
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
