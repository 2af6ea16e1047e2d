#!/usr/bin/env bash
# The build scripts' choice of compiler for the sanitizer builds
# (scripts/common.sh): clang only where it links the sanitizer's runtime, GCC
# otherwise, and a build folder's cache dropped when its compiler changes.
# Fake compilers and a fake cmake on PATH; nothing is built.
#   build_scripts_test.sh SOURCE_DIR
set -euo pipefail
source "$1/scripts/common.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Only the tools a case needs: bash, grep, rm and friends from the system,
# the compilers and cmake from a folder of fakes.
mkdir -p "$work/sys"
for tool in bash sh grep rm mkdir cat env dirname; do
  ln -s "$(command -v "$tool")" "$work/sys/$tool"
done
fake() {  # fake DIR NAME EXIT_STATUS: a tool that logs its arguments
  mkdir -p "$1"
  printf '#!/bin/sh\necho "$0 $*" >> %s/calls\nexit %s\n' "$work" "$3" > "$1/$2"
  chmod +x "$1/$2"
}

# No clang: nothing printed (the default compiler).
out=$(PATH=$work/sys whisker_sanitizer_compiler address)
[ -z "$out" ] || fail "without clang it chose '$out'"
# clang that cannot link the runtime (libclang-rt missing): nothing.
fake "$work/broken" clang++ 1; fake "$work/broken" clang 1
out=$(PATH=$work/broken:$work/sys whisker_sanitizer_compiler thread)
[ -z "$out" ] || fail "clang without its runtime was chosen: '$out'"
grep -q -- "-fsanitize=thread" "$work/calls" || fail "the probe did not ask for TSan's runtime"
# clang++ alone, without the C compiler beside it: nothing.
fake "$work/half" clang++ 0
out=$(PATH=$work/half:$work/sys whisker_sanitizer_compiler address)
[ -z "$out" ] || fail "clang++ without clang was chosen: '$out'"
# A clang that links it: clang++.
fake "$work/good" clang++ 0; fake "$work/good" clang 0
out=$(PATH=$work/good:$work/sys whisker_sanitizer_compiler address)
[ "$out" = clang++ ] || fail "a working clang was not chosen: '$out'"
grep -q -- "-fsanitize=address,undefined" "$work/calls" || fail "the probe did not ask for ASan + UBSan"

# The build folder: a cache for another compiler is dropped, one for the
# same compiler kept, and cmake is told the compiler's full path.
fake "$work/good" cmake 0
dir=$work/build-x
mkdir -p "$dir/CMakeFiles"
echo "CMAKE_CXX_COMPILER:FILEPATH=/usr/bin/c++" > "$dir/CMakeCache.txt"
: > "$work/calls"
PATH=$work/good:$work/sys WHISKER_VARIANT_CXX=clang++ whisker_build_variant "$dir" "-DX=1" all
[ ! -e "$dir/CMakeCache.txt" ] && [ ! -e "$dir/CMakeFiles" ] || fail "GCC's cache was kept for clang"
grep -q -- "-DX=1 -DCMAKE_CXX_COMPILER=$work/good/clang++ -DCMAKE_C_COMPILER=$work/good/clang" "$work/calls" ||
  fail "cmake was not told clang's path: $(cat "$work/calls")"
grep -q -- "--build $dir -j [0-9]* --target all" "$work/calls" || fail "the build was not run: $(cat "$work/calls")"

mkdir -p "$dir/CMakeFiles"
echo "CMAKE_CXX_COMPILER:FILEPATH=$work/good/clang++" > "$dir/CMakeCache.txt"
PATH=$work/good:$work/sys WHISKER_VARIANT_CXX=clang++ whisker_build_variant "$dir" "-DX=1"
[ -e "$dir/CMakeCache.txt" ] || fail "clang's own cache was dropped"

# Back to the default compiler: clang's cache is dropped.
PATH=$work/good:$work/sys whisker_build_variant "$dir" "-DX=1"
[ ! -e "$dir/CMakeCache.txt" ] || fail "clang's cache was kept for the default compiler"
echo "ok"
