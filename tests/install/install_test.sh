#!/bin/bash
# The installed tree: `cmake --install` into a prefix, moved elsewhere, the
# source tree hidden: --version, --help, a headless cat render, the messages
# that name the installed data folder.
#   install_test.sh BUILD_DIR SOURCE_DIR VERSION [VIEWER: ON|OFF]
set -uo pipefail
build=$1 src=$2 version=$3 viewer=${4:-ON}
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
source "$here/lib.sh"

p=$tmp/moved/prefix
install_prefix "$p"
for f in bin/whisker share/whisker/scenes/cat.json share/whisker/scenes/three-balls.json \
         share/whisker/cat.obj share/whisker/shaders/display.frag share/whisker/shaders/display.vert \
         share/doc/whisker/README.md share/man/man1/whisker.1.gz \
         share/applications/whisker.desktop share/icons/hicolor/256x256/apps/whisker.png; do
  [[ $f == */shaders/* && $viewer != ON ]] && continue
  [ -f "$p/$f" ] || fail "not installed: $f"
done
[ -x "$p/bin/whisker" ] || fail "bin/whisker is not executable"
# The binary holds no path into the build machine's source tree.
if grep -qF "$src" "$p/bin/whisker"; then fail "bin/whisker contains the source path $src"; fi

out=$(hidden "$p/bin/whisker" --version) || fail "--version failed"
[ "$out" = "whisker $version" ] || fail "--version printed '$out', expected 'whisker $version'"

hidden "$p/bin/whisker" --help >"$tmp/help" 2>&1 || fail "--help failed"
grep -q -- "--headless" "$tmp/help" && grep -q "Usage:" "$tmp/help" || fail "--help: $(head -3 "$tmp/help")"

# The cat, from the installed data: scene and mesh found beside the binary.
hidden "$p/bin/whisker" --headless --quiet --scene cat --target-spp 4 --out "$tmp/cwd/cat.png" \
  >"$tmp/render.log" 2>&1 || { cat "$tmp/render.log" >&2; fail "headless cat render failed"; }
python3 "$here/check_png.py" "$tmp/cwd/cat.png" 512 512 0.5 || fail "cat.png"

# A scene name that is not there: exit 2, the places looked in, a hint.
hidden "$p/bin/whisker" --headless --scene kat --out "$tmp/cwd/kat.png" 2>"$tmp/kat.err"
code=$?
[ $code -eq 2 ] || fail "--scene kat: exit $code, expected 2"
grep -qF "kat.json: scene file not found in $p/share/whisker/scenes" "$tmp/kat.err" ||
  fail "--scene kat: $(cat "$tmp/kat.err")"
grep -qF "did you mean --scene cat?" "$tmp/kat.err" || fail "--scene kat: no hint: $(cat "$tmp/kat.err")"
[ "$(wc -l <"$tmp/kat.err")" -eq 1 ] || fail "--scene kat: more than one line: $(cat "$tmp/kat.err")"
echo "installed tree OK: $version"
