#!/usr/bin/env bash
# Speed against error (issue 6): how much error Whisker leaves per second of
# rendering, for the report's method and for Whisker's best settings, on the
# same machine in the same run. Not part of the default test run.
#
#   bench/speed_vs_error.sh
#
# What it does:
#   1. builds whisker and whisker-compare (configures the build dir if needed);
#   2. renders, once, a reference per scene at REF_FACTOR (64) times the
#      largest study count (cached in $BUILD/references/, reused if present;
#      FORCE_REFS=1 renders them again), plus converged images of both
#      methods (AGREE_FACTOR x the largest count) for the agreement check;
#      the closed-form scene (closed-sphere, bench/convergence/closed_sphere.py)
#      gets its exact image instead of a rendered reference;
#   3. renders every scene at 1, 2, 4, ... MAX_SPP (cat: CAT_MAX_SPP, for the
#      issue's 1024-spp target) samples per pixel, SEEDS seeds, both methods
#      interleaved (so a change of machine load hits both alike), and measures
#      seconds (from --stats) and error against the reference (whisker-compare);
#   4. times the cat at full 512x512 for both methods (seconds per spp), for
#      the target's scaling;
#   5. writes $BUILD/convergence/results.csv, one log-log plot of MSE against
#      seconds per scene (PNG, gnuplot) and the markdown table
#      ($BUILD/convergence/table.md, also printed) that goes into
#      docs/PERFORMANCE.md.
#
# Methods: "report" = --sampler independent --zero-cutoff off --split 1 (independent
# uniform numbers, Gaussian jitter, fixed depth: the report's estimator);
# "best" = Whisker's defaults, whatever they are (the flags used are read back
# from the stats JSON into the CSV).
#
# The study renders at RES x RES (default 64; same camera and field of view)
# to stay within ~20 minutes on the 2-core machine; see docs/PERFORMANCE.md
# for what carries over to 512x512.
#
# Environment knobs: WHISKER_BUILD (build dir, default build/), RES, SEEDS,
# MAX_SPP, CAT_MAX_SPP, SCENES, CLOSED_RES, THREADS, REF_FACTOR, AGREE_FACTOR, BEST_FLAGS,
# FULLRES_SPP, FORCE_REFS, CONV_OUT (output dir, default $BUILD/convergence).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${WHISKER_BUILD:-$ROOT/build}
RES=${RES:-64}
SEEDS=${SEEDS:-"1 2 3"}
MAX_SPP=${MAX_SPP:-256}
CAT_MAX_SPP=${CAT_MAX_SPP:-1024}
SCENES=${SCENES:-"three-balls-fresnel indirect cat closed-sphere"}
CLOSED_RES=${CLOSED_RES:-32}  # every path of the closed sphere runs to full depth: smaller
THREADS=${THREADS:-$(nproc)}
REF_FACTOR=${REF_FACTOR:-64}     # reference spp = REF_FACTOR x MAX_SPP
AGREE_FACTOR=${AGREE_FACTOR:-16} # report-method converged image spp = AGREE_FACTOR x MAX_SPP
FULLRES_SPP=${FULLRES_SPP:-8}
FORCE_REFS=${FORCE_REFS:-0}
REF_SEED=1000
AGREE_SEED=2000
AGREE_BEST_SEED=3000

OUT=${CONV_OUT:-$BUILD/convergence}  # results of this run (runs/ is emptied at the start)
REFS=$BUILD/references
RUNS=$OUT/runs
SCENE_DIR=$OUT/scenes

# GNU time (Debian package "time") for the CPU-time column; without it the
# column stays empty.
no_timer() { shift; "$@"; }
TIMER=(/usr/bin/time -f "%U %S" -o)
[ -x /usr/bin/time ] || TIMER=(no_timer)
REPORT_FLAGS=(--sampler independent --zero-cutoff off --split 1 --split-weights 1,1,1 --connect off)
# Whisker best: the defaults, or BEST_FLAGS (e.g. "--split 1" for the
# single-path estimator the table in docs/PERFORMANCE.md was measured with).
read -r -a BEST_FLAGS <<<"${BEST_FLAGS:-}"

log() { printf '\033[1mspeed_vs_error:\033[0m %s\n' "$*" >&2; }

# --- tools ------------------------------------------------------------------
need_gnuplot() {
  command -v gnuplot >/dev/null 2>&1 && return 0
  local sudo=()
  [ "$(id -u)" -ne 0 ] && sudo=(sudo)
  log "installing gnuplot-nox"
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -q --no-install-recommends gnuplot-nox ||
    { "${sudo[@]}" apt-get update -q && DEBIAN_FRONTEND=noninteractive \
        "${sudo[@]}" apt-get install -y -q --no-install-recommends gnuplot-nox; }
}
need_gnuplot
command -v python3 >/dev/null 2>&1 || { log "python3 is needed for the analysis"; exit 1; }

if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$BUILD" -j 2 --target whisker whisker-compare
WHISKER=$BUILD/whisker
COMPARE=$BUILD/bench/convergence/whisker-compare
[ -x "$COMPARE" ] || COMPARE=$(find "$BUILD" -name whisker-compare -type f -perm -u+x | head -n1)
[ -x "$COMPARE" ] || { log "whisker-compare was not built"; exit 1; }

mkdir -p "$OUT" "$REFS" "$SCENE_DIR"
rm -rf "$RUNS"
mkdir -p "$RUNS" "$OUT/bin"
# Run private copies: a rebuild of the build dir during the run (another
# engineer, another run) must not swap the renderer in the middle of a study.
cp "$WHISKER" "$OUT/bin/whisker"
cp "$COMPARE" "$OUT/bin/whisker-compare"
WHISKER=$OUT/bin/whisker
COMPARE=$OUT/bin/whisker-compare

# A copy of a bundled scene at another resolution (same camera, same fov);
# for closed-sphere, the scene and its exact image.
res_of() { if [ "$1" = closed-sphere ]; then echo "$CLOSED_RES"; else echo "$RES"; fi; }
ref_of() {  # name -> reference image
  if [ "$1" = closed-sphere ]; then echo "$REFS/closed-sphere-$CLOSED_RES-exact.pfm"
  else echo "$REFS/$1-${RES}-sobol-zc-$REF_SPP.pfm"; fi
}
derive_scene() {  # name res -> path
  local name=$1 res=$2 dst=$SCENE_DIR/$1-$2.json
  if [ "$name" = closed-sphere ]; then
    python3 "$ROOT/bench/convergence/closed_sphere.py" "$dst" "$(ref_of closed-sphere)" "$res"
    echo "$dst"
    return
  fi
  python3 - "$ROOT/assets/scenes/$name.json" "$dst" "$res" <<'EOF'
import json, sys
src, dst, res = sys.argv[1], sys.argv[2], int(sys.argv[3])
scene = json.load(open(src))
scene["camera"]["width"] = res
scene["camera"]["height"] = res
json.dump(scene, open(dst, "w"), indent=2)
EOF
  echo "$dst"
}

render() {  # scene_file spp seed pfm stats flags...
  local scene=$1 spp=$2 seed=$3 pfm=$4 stats=$5
  shift 5
  # CPU time (user + system) beside the stats' wall-clock render time: on a
  # shared machine it is the steadier measure of the work done.
  "${TIMER[@]}" "$stats.cpu" "$WHISKER" --headless --quiet --scene "$scene" --frames 1 \
    --spp "$spp" --seed "$seed" --threads "$THREADS" --out-float "$pfm" --stats "$stats" "$@" \
    >/dev/null
}

pow2_list() {  # max -> 1 2 4 ... max
  local n=1 out=()
  while [ "$n" -le "$1" ]; do out+=("$n"); n=$((n * 2)); done
  echo "${out[@]}"
}

start=$(date +%s)
REF_SPP=$((REF_FACTOR * MAX_SPP))
AGREE_SPP=$((AGREE_FACTOR * MAX_SPP))
{
  echo "{"
  echo "  \"res\": $RES, \"closed_res\": $CLOSED_RES, \"threads\": $THREADS, \"ref_spp\": $REF_SPP, \"agree_spp\": $AGREE_SPP,"
  echo "  \"seeds\": \"$SEEDS\", \"nproc\": $(nproc),"
  echo "  \"cpu\": \"$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')\","
  echo "  \"commit\": \"$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)\","
  echo "  \"dirty\": $( [ -n "$(git -C "$ROOT" status --porcelain --untracked-files=no 2>/dev/null)" ] && echo true || echo false),"
  echo "  \"date\": \"$(date -u +%Y-%m-%dT%H:%MZ)\","
  echo "  \"load_at_start\": \"$(cut -d' ' -f1-3 /proc/loadavg)\""
  echo "}"
} >"$OUT/machine.json"

# --- 2. references (cached) -------------------------------------------------
for name in $SCENES; do
  res=$(res_of "$name")
  scene=$(derive_scene "$name" "$res")
  ref=$(ref_of "$name")
  agree=$REFS/$name-${res}-report-$AGREE_SPP.pfm
  if [ "$name" = closed-sphere ]; then
    echo '{"exact": true}' >"${ref%.pfm}.json"
  elif [ "$FORCE_REFS" = 1 ] || [ ! -f "$ref" ]; then
    # The reference is Whisker best itself (the same flags), so that its
    # own noise is C_best / REF_SPP in the agreement table below.
    log "reference $name ${RES}x$RES at $REF_SPP spp (Whisker best)"
    render "$scene" "$REF_SPP" "$REF_SEED" "$ref" "${ref%.pfm}.json" ${BEST_FLAGS[@]+"${BEST_FLAGS[@]}"}
  fi
  if [ "$FORCE_REFS" = 1 ] || [ ! -f "$agree" ]; then
    log "converged report-method image $name ${res}x$res at $AGREE_SPP spp"
    render "$scene" "$AGREE_SPP" "$AGREE_SEED" "$agree" "${agree%.pfm}.json" "${REPORT_FLAGS[@]}"
  fi
  agree_best=$REFS/$name-${res}-best-$AGREE_SPP.pfm
  if [ "$FORCE_REFS" = 1 ] || [ ! -f "$agree_best" ]; then
    log "converged Whisker-best image $name ${res}x$res at $AGREE_SPP spp"
    render "$scene" "$AGREE_SPP" "$AGREE_BEST_SEED" "$agree_best" "${agree_best%.pfm}.json" \
      ${BEST_FLAGS[@]+"${BEST_FLAGS[@]}"}
  fi
  "$COMPARE" "$agree" "$ref" --json "$RUNS/agree-$name.json" >/dev/null
  "$COMPARE" "$agree_best" "$ref" --json "$RUNS/agree-best-$name.json" >/dev/null
  "$COMPARE" "$agree" "$agree_best" --json "$RUNS/agree-pair-$name.json" >/dev/null
  cp "${ref%.pfm}.json" "$RUNS/ref-$name.stats.json"
  cp "${agree%.pfm}.json" "$RUNS/agree-$name.stats.json"
  cp "${agree_best%.pfm}.json" "$RUNS/agree-best-$name.stats.json"
done

# --- 3. the study -----------------------------------------------------------
for name in $SCENES; do
  scene=$SCENE_DIR/$name-$(res_of "$name").json
  ref=$(ref_of "$name")
  max=$MAX_SPP
  [ "$name" = cat ] && max=$CAT_MAX_SPP
  log "$name: spp $(pow2_list "$max"), seeds $SEEDS"
  for spp in $(pow2_list "$max"); do
    for seed in $SEEDS; do
      for method in report best; do
        flags=("${BEST_FLAGS[@]}")
        [ "$method" = report ] && flags=("${REPORT_FLAGS[@]}")
        base=$RUNS/$name-$method-$spp-$seed
        cut -d' ' -f1 /proc/loadavg >"$base.load"
        render "$scene" "$spp" "$seed" "$base.pfm" "$base.stats.json" ${flags[@]+"${flags[@]}"}
        "$COMPARE" "$base.pfm" "$ref" --json "$base.cmp.json" >/dev/null
        rm -f "$base.pfm"
      done
    done
  done
done

# --- 4. the cat at full resolution: seconds per spp --------------------------
if [[ " $SCENES " == *" cat "* ]]; then
  log "cat 512x512 at $FULLRES_SPP spp, both methods (timing only)"
  for method in report best; do
    flags=("${BEST_FLAGS[@]}")
    [ "$method" = report ] && flags=("${REPORT_FLAGS[@]}")
    render "$ROOT/assets/scenes/cat.json" "$FULLRES_SPP" 1 "$RUNS/fullres-$method.pfm" \
      "$RUNS/fullres-$method.stats.json" ${flags[@]+"${flags[@]}"}
    rm -f "$RUNS/fullres-$method.pfm"
  done
fi

end=$(date +%s)
log "renders took $((end - start)) s"
echo "{\"wall_seconds\": $((end - start)), \"load_at_end\": \"$(cut -d' ' -f1-3 /proc/loadavg)\"}" >"$OUT/run.json"

# --- 5. CSV, plots, table ---------------------------------------------------
python3 "$ROOT/bench/convergence/analyze.py" "$OUT" | tee "$OUT/table.md"
for gp in "$OUT"/*.gp; do gnuplot "$gp"; done
log "wrote $OUT/results.csv, $OUT/table.md and $(ls "$OUT"/*.png | tr '\n' ' ')"
