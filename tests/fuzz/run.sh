#!/usr/bin/env bash
# Bounded fuzzing of the scene reader, the OBJ loader and the part reader with libFuzzer.
#   tests/fuzz/run.sh [SECONDS] [JOBS]   SECONDS per harness (default 60)
# Builds the harnesses with clang into build-fuzz/ (or $WHISKER_FUZZ_BUILD),
# seeds each from tests/fuzz/corpus and the reproducers, and fuzzes into a
# working corpus under the build folder (the repository's corpus is never
# modified). A crash leaves its input as build-fuzz/findings/<harness>/crash-*
# and fails the script. Exit 77 when clang is missing (the caller skips).
#
# Long runs (hours, all cores), e.g. overnight:
#   tests/fuzz/run.sh 28800 "$(nproc)"
# then minimise a crash with
#   build-fuzz/fuzz_obj -minimize_crash=1 -runs=100000 build-fuzz/findings/obj/crash-...
# and copy the result to tests/fuzz/reproducers/<harness>/ with a name that
# says what it does.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
seconds=${1:-60}
jobs=${2:-1}
build=${WHISKER_FUZZ_BUILD:-$root/build-fuzz}

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: clang++ not found; skipping the fuzz run (apt-get install clang)" >&2
  exit 77
fi
# Debian's clang recommends, but does not require, the runtime with libFuzzer.
if ! echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }' |
    clang++ -x c++ -fsanitize=fuzzer,address,undefined - -o /dev/null 2>/dev/null; then
  echo "fuzz: clang++ cannot link -fsanitize=fuzzer; skipping (apt-get install libclang-rt-14-dev)" >&2
  exit 77
fi
cmake -S "$here" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)"

# Known third-party noise only (none needed so far); halt on the first report.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

status=0
cd "$build"  # libFuzzer's -jobs logs (fuzz-N.log) land here
for name in scene obj part; do
  work="$build/corpus/$name" findings="$build/findings/$name"
  mkdir -p "$work" "$findings"
  log="$build/fuzz_$name.log"
  echo "fuzz: $name for ${seconds} s ($jobs job(s)); log $log" >&2
  # -timeout: one input taking over 10 s is a finding (a hang); -rss_limit_mb
  # likewise for memory. Inputs up to 64 KiB reach every construct of both
  # formats. stdin is closed: no input may wait on the terminal.
  par=()
  [ "$jobs" -gt 1 ] && par=(-jobs="$jobs" -workers="$jobs")
  if ! "$build/fuzz_$name" "$work" "$here/corpus/$name" "$here/reproducers/$name" \
      -dict="$here/$name.dict" -max_total_time="$seconds" -max_len=65536 \
      -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$findings/" \
      "${par[@]}" -print_final_stats=1 </dev/null >"$log" 2>&1; then
    status=1
    echo "fuzz: $name FOUND A CRASH; inputs in $findings; last lines of the log:" >&2
    tail -n 40 "$log" >&2
  fi
  # With -jobs the per-worker logs are fuzz-N.log in the working folder.
  grep -h "stat::number_of_executed_units\|Done [0-9]* runs" "$log" fuzz-*.log >&2 2>/dev/null || true
done
exit $status
