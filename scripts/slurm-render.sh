#!/usr/bin/env bash
# Renders SCENE at SPP samples per pixel as a Slurm job array of TASKS sample
# ranges, then merges the parts in a job that runs once every task succeeded.
#
#   scripts/slurm-render.sh SCENE SPP TASKS [OUT.exr]
#
# Task i renders samples [i*SPP/TASKS, (i+1)*SPP/TASKS) as one pass into
# OUT.parts/part-i.exr; the merge writes OUT.exr (accumulation file) and
# OUT.png. The merge equals bit for bit `whisker --headless --samples 0:SPP
# --spp SPP/TASKS` on one machine (when TASKS divides SPP; docs/SHARDS.md).
# OUT's folder must be visible to every node (a shared file system).
#
# Environment:
#   WHISKER       the whisker binary, as the nodes see it (default: build/whisker here)
#   WHISKER_ARGS  more options for every part, e.g. "--indirect on --seed 3"
#   SBATCH_ARGS   more sbatch options for both jobs, e.g. "--partition=long --time=4:00:00"
#   WAIT=1        block until the merge job ends (sbatch --wait); exit with its status
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/render_parts_args.sh"
render_parts_args sbatch "sbatch not found: is Slurm installed here?" "$@"
read -r -a sbatch_args <<<"${SBATCH_ARGS:-}"

# One script per job, kept beside the parts for the record.
cat >"$parts/part.sbatch" <<JOB
#!/usr/bin/env bash
#SBATCH --job-name=whisker-part
#SBATCH --output=$parts/part-%a.log
set -euo pipefail
i=\$SLURM_ARRAY_TASK_ID
begin=\$(( i * $spp / $tasks )) end=\$(( (i + 1) * $spp / $tasks ))
exec "$whisker" --headless --quiet --scene "$scene" ${WHISKER_ARGS:-} \\
  --threads "\${SLURM_CPUS_PER_TASK:-0}" --samples "\$begin:\$end" --spp "\$(( end - begin ))" \\
  --out-sum "$parts/part-\$i.exr"
JOB
files=()
for ((i = 0; i < tasks; ++i)); do files+=("$parts/part-$i.exr"); done
cat >"$parts/merge.sbatch" <<JOB
#!/usr/bin/env bash
#SBATCH --job-name=whisker-merge
#SBATCH --output=$parts/merge.log
exec "$whisker" merge $(printf '%q ' "${files[@]}")--out "$out" --out "${out%.exr}.png"
JOB

array=$(sbatch --parsable "${sbatch_args[@]}" --array="0-$((tasks - 1))" "$parts/part.sbatch")
array=${array%%;*}
wait_args=()
[ "${WAIT:-0}" = 1 ] && wait_args=(--wait)
echo "parts: job array $array ($tasks tasks) -> $parts"
echo "merge: after every part succeeds -> $out"
sbatch --parsable "${sbatch_args[@]}" "${wait_args[@]}" --dependency="afterok:$array" \
  --kill-on-invalid-dep=yes "$parts/merge.sbatch"
