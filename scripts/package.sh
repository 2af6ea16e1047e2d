#!/bin/bash
# Builds the Debian package of Whisker: configures and builds build/ (as
# scripts/run.sh does, installing what is missing), then `cpack -G DEB`.
#   scripts/package.sh [OUTDIR]     (default: build/) -> OUTDIR/whisker_<version>_<arch>.deb
# Depends is computed from the linked shared libraries (dpkg-shlibdeps).
set -euo pipefail
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
out=${1:-$WHISKER_BUILD}
whisker_install
whisker_build whisker whisker_man
mkdir -p "$out"
out=$(cd "$out" && pwd)
(cd "$WHISKER_BUILD" && cpack -G DEB -B "$out" >/dev/null)
rm -rf "$out/_CPack_Packages"
ls "$out"/whisker_*.deb
