#!/bin/bash
# Renders the application icon, packaging/whisker.png (256 x 256), with
# Whisker itself: the cat scene seen closer (packaging/icon.json).
#   packaging/render-icon.sh [path/to/whisker]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/whisker}
"$bin" --headless --quiet --scene "$here/icon.json" --out "$here/whisker.png"
