#!/usr/bin/env bash
# Installs what is missing, builds Whisker and runs its tests through ctest.
#
#   scripts/test.sh                 everything CI runs, in this order:
#                                   1. Release build, every test (ctest);
#                                   2. the core tests under ASan + UBSan, then TSan;
#                                   3. bounded fuzzing (when clang is present).
#   scripts/test.sh --normal        step 1 only (the quick check while working)
#   scripts/test.sh --sanitize      step 2 only
#   scripts/test.sh --fuzz [SECS]   step 3 only (SECS per harness; default 10)
#   scripts/test.sh --sanitize-viewer
#                                   the viewer tests too under ASan + UBSan (Xvfb; slow)
# Arguments after -- go to ctest (e.g. -- -R Sphere).
# WHISKER_FUZZ_SECONDS sets the fuzzing time per harness of the full run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

# The full run fuzzes 10 s per harness: a smoke test that every harness
# builds, replays its corpus and survives fresh mutations, inside CI's time
# budget; long runs are tests/fuzz/run.sh's job (see its header).
steps=() fuzz_seconds=${WHISKER_FUZZ_SECONDS:-10} ctest_args=()
while [ $# -gt 0 ]; do
  case $1 in
    --normal) steps+=(normal) ;;
    --sanitize) steps+=(asan tsan) ;;
    --sanitize-viewer) steps+=(asan-viewer) ;;
    --fuzz)
      steps+=(fuzz)
      if [ $# -gt 1 ] && [[ $2 =~ ^[0-9]+$ ]]; then fuzz_seconds=$2; shift; fi
      ;;
    --) shift; ctest_args=("$@"); break ;;
    *) ctest_args+=("$1") ;;  # as before: anything else is for ctest
  esac
  shift
done
[ ${#steps[@]} -gt 0 ] || steps=(normal asan tsan fuzz)

jobs=$(nproc 2>/dev/null || echo 2)
# Too slow under the sanitizers for the CI budget, and covered there by
# nothing a sanitizer would add: 20 s of one thread adding millions of
# samples in Release (5-10x that under ASan/TSan); it shares its code path
# with the shorter Progressive.* tests, which do run.
# The linear-time scene parse: a timing test of 400k objects (the parser's
# memory safety is the scene fuzzer's job, which runs under ASan + UBSan).
# The cat room's channel means with and without light connections: eight
# renders of 32x64 pixels through the code that
# LightConnect.CatRoomKeepsEachPixelsExpectation runs too, and a statistical
# check (the slowest core test under both sanitizers, 20-40 s).
sanitizer_exclude='^Accumulation\.MillionsOfSamplesKeepPrecision$|^Faults\.scene-parse|^LightConnect\.CatRoomKeepsEachChannelsImageMean$'
# TSan looks for data races, and only the renderer (src/render/progressive.*)
# starts threads: the suites of the geometry and scene layers, which never
# do, run under ASan + UBSan only (they are most of the TSan run's time).
# The hard cases too: each is single renders through the same threaded code
# as the Headless.* tests, checked for numbers (ASan + UBSan run them). So
# are the shard and command-line suites (processes, files and merges around
# the same renderer). The test files holding only such suites are not even
# built under TSan (tests/CMakeLists.txt).
# The estimators' agreement with closed forms and per-pixel images
# (Estimators/, Splits/) check numbers, renders of one pass
# through the same workers as the Progressive.* and LightConnect.* tests,
# which do run, as do the Headless.* tests but the one that renders every
# sphere scene (ASan + UBSan run it).
# A second request's deadline (stopped within 1 s) does not hold under TSan,
# which defers a signal's handler to its own safe points; ASan + UBSan and
# the Release build run those two cases.
tsan_exclude="$sanitizer_exclude|^Faults\.(second-request-stops-at-once|same-signal-later-is-a-second-request)$|^(Bvh|ObjectBvh|LightBuffer|Sphere|Triangle|Sampler|MeshIo|SceneFiles|World|Fuzz|HardCase|Shards|CommandLineE2E|)\.|^(Estimators|Splits)/|^Headless\.EverySphereScene"
# The core tests: unit, end-to-end, fuzz replays, faults (not the benches,
# not the viewer, which the sanitizer builds leave out).
sanitizer_targets=(whisker whisker_tests fuzz_scene_replay fuzz_obj_replay fuzz_part_replay)

declare -A took
timed() {
  local name=$1 t0=$SECONDS
  shift
  whisker_log "step $name"
  "$@"
  took[$name]=$((SECONDS - t0))
  whisker_log "step $name: ${took[$name]} s"
}

# Twice as many tests as cores at once: the viewer's window tests and the
# cluster scripts' spend most of their time waiting (keys held for frames,
# a queue's polls), and beside them the rest keep the cores busy.
run_normal() {
  whisker_build
  (cd "$WHISKER_BUILD" && ctest --output-on-failure -j "$((jobs * 2))" "${ctest_args[@]}")
}

# run_sanitized NAME SANITIZER [cmake args]: build the core tests into
# build-NAME and run them with the sanitizer's options.
run_sanitized() {
  local name=$1 san=$2 extra=${3:-} dir=$WHISKER_ROOT/build-$1 targets=("${sanitizer_targets[@]}")
  local cxx=
  [ "$name" = asan-viewer ] && targets=()  # everything, viewer included
  # The viewer's sanitizer build keeps GCC: its suppressions and the ImGui
  # backends' recoverable bounds checks were written for it.
  [ "$name" = asan-viewer ] || cxx=$(whisker_sanitizer_compiler "$san")
  whisker_log "$name: compiler ${cxx:-default (c++)}"
  # No header checks: they catch wrong includes, which the Release build
  # already did, and would compile 45 more files per sanitizer.
  WHISKER_VARIANT_CXX=$cxx whisker_build_variant "$dir" "-DCMAKE_BUILD_TYPE=RelWithDebInfo -DWHISKER_SANITIZE=$san \
    -DWHISKER_BENCH=OFF -DWHISKER_VIEWER=OFF -DWHISKER_HEADER_CHECKS=OFF $extra" "${targets[@]}"
  (
    whisker_sanitizer_env
    cd "$dir"
    local label=()
    [ "$name" = asan-viewer ] && label=(-L viewer)
    local exclude=$sanitizer_exclude
    [ "$san" = thread ] && exclude=$tsan_exclude
    # The cluster scripts' tests (Slurm, GNU parallel) exercise shell and
    # daemons, not more of Whisker's code than the shard tests: once is enough.
    # The install tests package and install the build's binaries: a
    # sanitizer build builds only the core targets (no man page, no icon),
    # and a sanitized binary is nothing to package; Release runs them.
    ctest --output-on-failure -j "$jobs" -E "$exclude" -LE 'cluster|install' "${label[@]}" "${ctest_args[@]}"
  )
}

run_fuzz() {
  local rc=0
  bash "$WHISKER_ROOT/tests/fuzz/run.sh" "$fuzz_seconds" || rc=$?
  if [ "$rc" -eq 77 ]; then
    whisker_log "fuzzing skipped: no clang"
    return 0
  fi
  return "$rc"
}

whisker_install
for step in "${steps[@]}"; do
  case $step in
    normal) timed normal run_normal ;;
    asan) timed asan run_sanitized asan address ;;
    tsan) timed tsan run_sanitized tsan thread ;;
    asan-viewer) timed asan-viewer run_sanitized asan-viewer address -DWHISKER_VIEWER=ON ;;
    fuzz) timed fuzz run_fuzz ;;
  esac
done
for step in "${steps[@]}"; do whisker_log "time: $step ${took[$step]} s"; done
