#!/bin/bash
# The desktop entry passes desktop-file-validate, launches whisker with a
# file (%f) in the Graphics category, and names an icon that is installed
# as a 256 x 256 PNG of the picture Whisker rendered.
#   desktop_test.sh SOURCE_DIR
set -uo pipefail
src=$1
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
entry=$src/packaging/whisker.desktop
command -v desktop-file-validate >/dev/null || fail "desktop-file-validate missing (desktop-file-utils)"
out=$(desktop-file-validate "$entry" 2>&1) || fail "desktop-file-validate: $out"
[ -z "$out" ] || fail "desktop-file-validate warns: $out"
key() { sed -n "s/^$1=//p" "$entry"; }
[ "$(key Exec)" = "whisker %f" ] || fail "Exec=$(key Exec)"
[ "$(key Icon)" = whisker ] || fail "Icon=$(key Icon)"
[ "$(key Type)" = Application ] || fail "Type=$(key Type)"
case ";$(key Categories)" in *";Graphics;"*) ;; *) fail "Categories=$(key Categories)" ;; esac
python3 "$here/check_png.py" "$src/packaging/whisker.png" 256 256 0.9 || fail "the icon"
echo "desktop entry OK"
