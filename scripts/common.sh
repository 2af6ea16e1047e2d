# Shared by run.sh and test.sh: install what is missing, configure, build.
# Sourced, not run.

WHISKER_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WHISKER_BUILD=${WHISKER_BUILD:-$WHISKER_ROOT/build}

# Debian packages the build and the tests need.
WHISKER_PACKAGES=(
  g++ make cmake pkg-config python3
  clang libclang-rt-14-dev  # the fuzzers: libFuzzer's runtime is only recommended by clang-14
  libglm-dev nlohmann-json3-dev libcli11-dev libtinyobjloader-dev libstb-dev libopenexr-dev
  libgtest-dev libbenchmark-dev libembree-dev
  libglfw3-dev libimgui-dev python3-glad libgl-dev libgl1-mesa-dri xvfb xauth xdotool
  x11-apps  # xwd: the viewer tests' screenshots of the real window
  dpkg-dev file desktop-file-utils man-db  # the package (dpkg-shlibdeps; CPack's DEB generator runs file) and its checks
)

whisker_log() { printf '\033[1mwhisker:\033[0m %s\n' "$*" >&2; }

whisker_install() {
  local missing=() p
  for p in "${WHISKER_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      whisker_log "missing packages: ${missing[*]}; run as root or install sudo"
      return 1
    fi
  fi
  whisker_log "installing: ${missing[*]}"
  "${sudo[@]}" apt-get update -q || return 1
  # Through env: sudo drops DEBIAN_FRONTEND from the environment.
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}" || return 1
}

# whisker_build [target...]: configure and build the given targets (default: all).
whisker_build() {
  local jobs targets=()
  [ $# -gt 0 ] && targets=(--target "$@")
  jobs=$(nproc 2>/dev/null || echo 2)
  # Always configure: cheap when nothing changed, and it recovers a build
  # directory left behind by a failed configure (cache but no Makefile).
  cmake -S "$WHISKER_ROOT" -B "$WHISKER_BUILD" -DCMAKE_BUILD_TYPE=Release || return 1
  cmake --build "$WHISKER_BUILD" -j "$jobs" "${targets[@]}" || return 1
}

# whisker_build_variant DIR "CMAKE ARGS..." [target...]: configure and build
# another build folder (the sanitizer builds) with its own cache settings.
# With WHISKER_VARIANT_CXX set (a C++ compiler's name, e.g. clang++), the
# folder is built with that compiler (and its C sibling); a cache left by
# another compiler is removed first, since CMake cannot switch in place.
whisker_build_variant() {
  local dir=$1 args=$2 jobs targets=() cxx=${WHISKER_VARIANT_CXX:-}
  shift 2
  [ $# -gt 0 ] && targets=(--target "$@")
  jobs=$(nproc 2>/dev/null || echo 2)
  if [ -n "$cxx" ]; then
    local cxx_path cc_path
    cxx_path=$(command -v "$cxx") || { whisker_log "no compiler $cxx"; return 1; }
    cc_path=$(command -v "${cxx%++}") || { whisker_log "no compiler ${cxx%++}"; return 1; }
    if [ -f "$dir/CMakeCache.txt" ] &&
        ! grep -qx "CMAKE_CXX_COMPILER:[A-Z]*=$cxx_path" "$dir/CMakeCache.txt"; then
      rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
    fi
    args="$args -DCMAKE_CXX_COMPILER=$cxx_path -DCMAKE_C_COMPILER=$cc_path"
  elif [ -f "$dir/CMakeCache.txt" ] && grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=.*clang" "$dir/CMakeCache.txt"; then
    rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"  # back to the default compiler
  fi
  # shellcheck disable=SC2086
  cmake -S "$WHISKER_ROOT" -B "$dir" $args >/dev/null || return 1
  cmake --build "$dir" -j "$jobs" "${targets[@]}" || return 1
}

# whisker_sanitizer_compiler SAN (address or thread): prints clang++ when
# clang is installed and links that sanitizer's runtime, else nothing (the
# default compiler, GCC). The sanitizer builds of scripts/test.sh use it:
# on the project's 2-core machine clang built the ASan + UBSan step in 165 s
# against GCC's 252 s, and its tests ran in 161 s against 201 s (TSan: 92 +
# 53 s against 103 + 83 s).
whisker_sanitizer_compiler() {
  local flags=-fsanitize=address,undefined
  [ "$1" = thread ] && flags=-fsanitize=thread
  command -v clang++ >/dev/null 2>&1 && command -v clang >/dev/null 2>&1 || return 0
  # A here-string, not a pipe: a compiler that exits before reading its input
  # would fail the pipe's writer under pipefail, whatever the compiler said.
  clang++ -x c++ "$flags" - -o /dev/null <<<'int main() { return 0; }' >/dev/null 2>&1 || return 0
  echo clang++
}

# The sanitizers' run-time options: every finding fails its test, and the
# suppression files (third-party noise only, reasons inside) apply.
whisker_sanitizer_env() {
  local supp=$WHISKER_ROOT/tests/sanitizers
  export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
  export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$supp/ubsan.supp"
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp"
}
