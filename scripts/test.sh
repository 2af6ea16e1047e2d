#!/usr/bin/env bash
# Installs what is missing, builds Whisker and runs every test through ctest.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
whisker_install
whisker_build
cd "$WHISKER_BUILD"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
