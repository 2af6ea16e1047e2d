#!/bin/bash
# Builds the Debian package of Whisker: configures and builds build-package/
# (installing what is missing) for any x86-64 processor with AVX2 and FMA
# (-DWHISKER_NATIVE=OFF: a package built with -march=native would run only on
# processors like the one that built it), installs it into a staging folder
# (`cmake --install --strip`, prefix /usr) and packages that with
# `cpack -G DEB` (the settings in cmake/install.cmake; Depends from the
# linked libraries through dpkg-shlibdeps).
#   scripts/package.sh [--no-build] [OUTDIR]   -> OUTDIR/whisker_<version>_<arch>.deb
# OUTDIR defaults to the build folder. --no-build packages $WHISKER_BUILD
# (default build/) as it is (the tests use it: packaging never rebuilds under
# a running test).
set -euo pipefail
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
build=1
if [ "${1:-}" = --no-build ]; then build=0; shift; fi
if [ $build = 1 ]; then
  WHISKER_BUILD=$WHISKER_ROOT/build-package
  whisker_install
  whisker_build_variant "$WHISKER_BUILD" "-DCMAKE_BUILD_TYPE=Release -DWHISKER_NATIVE=OFF \
    -DWHISKER_TESTS=OFF -DWHISKER_BENCH=OFF -DWHISKER_HEADER_CHECKS=OFF" whisker whisker_man
fi
out=${1:-$WHISKER_BUILD}
[ -x "$WHISKER_BUILD/whisker" ] || { whisker_log "no $WHISKER_BUILD/whisker: build first"; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/whisker-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
stage=$work/root
cmake --install "$WHISKER_BUILD" --prefix "$stage/usr" --strip >/dev/null
# Package the staged tree as it is; cpack's own install step would first run
# the build's preinstall target, which builds.
(cd "$WHISKER_BUILD" && cpack -G DEB -B "$out" -D CPACK_INSTALL_CMAKE_PROJECTS= \
  -D "CPACK_INSTALLED_DIRECTORIES=$stage;.") >"$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log" >&2; exit 1; }
rm -rf "$out/_CPack_Packages"
ls "$out"/whisker_*.deb
