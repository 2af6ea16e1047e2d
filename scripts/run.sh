#!/usr/bin/env bash
# Installs what is missing, builds Whisker (Release, into build/) and runs it.
#   scripts/run.sh                 the viewer on the cat scene (headless render without a display)
#   scripts/run.sh --headless ...  any whisker options
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
whisker_install
whisker_build whisker >&2  # just the program, not the tests and benchmarks

if [ $# -gt 0 ]; then
  exec "$WHISKER_BUILD/whisker" "$@"
fi
status=0
"$WHISKER_BUILD/whisker" || status=$?
if [ "$status" -eq 3 ]; then
  # No display: render the default scene without a window instead. The cat's
  # own target (1024 samples per pixel) takes minutes on two cores; 32 give
  # about the noise of the report's program at 1024, at every scale.
  # More: --target-spp N or --frames N.
  out="$PWD/whisker-cat.png"
  whisker_log "no display; rendering the cat scene headless (32 samples per pixel) to $out"
  exec "$WHISKER_BUILD/whisker" --headless --scene cat --target-spp 32 --out "$out"
fi
exit "$status"
