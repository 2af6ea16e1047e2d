#!/bin/bash
# The viewer from an installed tree moved elsewhere, under Xvfb: it finds its
# shaders and scenes beside the binary (the source tree hidden) and saves
# one screenshot.
#   viewer_test.sh BUILD_DIR SOURCE_DIR   (exit 77: skipped, no xvfb-run)
set -uo pipefail
build=$1 src=$2
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
source "$here/lib.sh"
command -v xvfb-run >/dev/null || { echo "xvfb-run not installed: skipped"; exit 77; }

p=$tmp/moved/prefix
install_prefix "$p"
hidden xvfb-run -a -s '-screen 0 1280x800x24' env LIBGL_ALWAYS_SOFTWARE=1 \
  "$p/bin/whisker" --scene three-balls --threads 1 --frames 2 --screenshot shot.png \
  >"$tmp/viewer.log" 2>&1 || { cat "$tmp/viewer.log" >&2; fail "the installed viewer failed"; }
[ -f "$tmp/cwd/shot.png" ] || fail "no screenshot"
size=$(python3 -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); print(*struct.unpack(">II", d[16:24]))' "$tmp/cwd/shot.png")
read -r w h <<<"$size"
[ "$w" -ge 512 ] && [ "$h" -ge 512 ] || fail "screenshot is ${w}x$h"
python3 "$here/check_png.py" "$tmp/cwd/shot.png" "$w" "$h" 0.5 || fail "screenshot"
echo "installed viewer OK"
