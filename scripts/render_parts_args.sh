# Sourced by slurm-render.sh and parallel-render.sh: reads and checks their
# common arguments, SCENE SPP TASKS [OUT.exr], and sets scene, spp, tasks,
# out (absolute), parts (OUT's parts folder, created), root and whisker.
# $1 is the command the caller needs on PATH, $2 the hint if it is missing.

render_parts_args() {
  local need=$1 hint=$2
  shift 2
  local me=${BASH_SOURCE[1]}
  [ $# -ge 3 ] && [ $# -le 4 ] || { echo "usage: $me SCENE SPP TASKS [OUT.exr]" >&2; exit 2; }
  scene=$1 spp=$2 tasks=$3
  out=${4:-$PWD/$(basename "${scene%.json}")-$spp.exr}
  [[ $spp =~ ^[1-9][0-9]*$ && $tasks =~ ^[1-9][0-9]*$ ]] || { echo "$me: SPP and TASKS must be positive integers" >&2; exit 2; }
  [ "$tasks" -le "$spp" ] || { echo "$me: TASKS ($tasks) must be at most SPP ($spp)" >&2; exit 2; }
  [[ $out == *.exr ]] || { echo "$me: OUT must end in .exr, got $out" >&2; exit 2; }
  command -v "$need" >/dev/null || { echo "$me: $hint" >&2; exit 2; }
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  whisker=${WHISKER:-$root/build/whisker}
  [ -x "$whisker" ] || { echo "$me: $whisker is not an executable (set WHISKER)" >&2; exit 2; }
  out=$(realpath -m "$out")
  [[ $scene == */* || $scene == *.json ]] && scene=$(realpath "$scene")
  parts=${out%.exr}.parts
  mkdir -p "$parts"
}
