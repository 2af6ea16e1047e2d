# Sourced by the benchmark scripts: builds the report's own program and runs it
# beside Whisker, so every comparison is measured in the same run.
#
#   REPORT_PROGRAM_DIR  its source and build script (default: ../shared/seed/program
#                       beside the checkout; the bench stops with a message if absent)
#   report_program_build OUT_DIR      -> sets REPORT_CAT (cat, bugs mended) and
#                                        REPORT_BALLS (three balls, bugs mended)
#   report_program_run BINARY SPP SEED PFM -> prints the program's wall seconds
#
# The program is the report's, unchanged but for what its build script patches
# in (samples per pixel from NUM_RAYS, SEED, a PFM of linear radiance) and its two
# bugs mended (--fixed), so that its converged image is the one Whisker renders
# and the errors of the two compare. It reads cat.obj from its working directory.

REPORT_PROGRAM_DIR=${REPORT_PROGRAM_DIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/shared/seed/program}

report_program_build() {
  local out=$1
  if [ ! -f "$REPORT_PROGRAM_DIR/main.cpp" ] || [ ! -f "$REPORT_PROGRAM_DIR/build.sh" ]; then
    echo "the report's program is not at $REPORT_PROGRAM_DIR (main.cpp and build.sh);" \
         "set REPORT_PROGRAM_DIR" >&2
    return 1
  fi
  mkdir -p "$out/report"
  REPORT_CAT=$out/report/raytracer-cat
  REPORT_BALLS=$out/report/raytracer-balls
  bash "$REPORT_PROGRAM_DIR/build.sh" "$REPORT_PROGRAM_DIR/main.cpp" "$REPORT_CAT" --fixed
  bash "$REPORT_PROGRAM_DIR/build.sh" "$REPORT_PROGRAM_DIR/main.cpp" "$REPORT_BALLS" --balls --fixed
  cp "$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/assets/cat.obj" "$out/report/cat.obj"
}

# Wall seconds of the whole process (it loads the cat and builds its BVH too).
report_program_run() {
  local bin=$1 spp=$2 seed=$3 pfm=$4 t0 t1
  t0=$(date +%s.%N)
  (cd "$(dirname "$bin")" && NUM_RAYS=$spp SEED=$seed PFM_OUT=$pfm OMP_NUM_THREADS=${THREADS:-2} \
     "$bin" >/dev/null)
  t1=$(date +%s.%N)
  python3 -c "print(f'{$t1 - $t0:.3f}')"
}
