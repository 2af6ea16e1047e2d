#!/bin/bash
# Where --scene NAME is looked up, in order: $WHISKER_SCENES, then
# $WHISKER_ASSETS/scenes, then ./assets/scenes, then the data folder beside
# the binary; a name found nowhere lists them all. And the positional FILE:
# a .json scene, or an .obj shown in the cat's room.
#   scene_lookup_test.sh WHISKER_BIN SOURCE_DIR
set -uo pipefail
bin=$1 src=$2 build=
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
source "$here/lib.sh"
unset WHISKER_ASSETS WHISKER_SCENES

# A small copy of a bundled scene under another name, with the cat's mesh path.
small() {  # file name
  mkdir -p "$(dirname "$1")"
  python3 - "$src/assets/scenes/three-balls.json" "$1" "$2" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["name"] = sys.argv[3]
s["camera"]["width"], s["camera"]["height"] = 24, 16
json.dump(s, open(sys.argv[2], "w"))
PY
}
# The scene name a run of `--scene three-balls` (or other arguments) rendered.
rendered() {
  (cd "$tmp/cwd" && "$bin" --headless --quiet --frames 1 --stats "$tmp/s.json" "$@") \
    >"$tmp/run.log" 2>&1 || { cat "$tmp/run.log" >&2; return 1; }
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["scene"])' "$tmp/s.json"
}
expect() {  # want args...
  local want=$1 got
  shift
  got=$(rendered "$@") || fail "$* failed"
  [ "$got" = "$want" ] || fail "$*: rendered scene '$got', expected '$want'"
}

mkdir -p "$tmp/cwd"
# Nothing here: the data folder beside the binary (the build's assets link).
expect three-balls --scene three-balls
# The working folder's own assets/scenes wins over the data folder.
small "$tmp/cwd/assets/scenes/three-balls.json" from-cwd
expect from-cwd --scene three-balls
# $WHISKER_ASSETS/scenes wins over the working folder; $WHISKER_SCENES over both.
small "$tmp/assets/scenes/three-balls.json" from-assets
WHISKER_ASSETS=$tmp/assets expect from-assets --scene three-balls
small "$tmp/scenes/three-balls.json" from-scenes
WHISKER_SCENES=$tmp/scenes WHISKER_ASSETS=$tmp/assets expect from-scenes --scene three-balls
# A path is a path, never a name.
expect from-assets --scene "$tmp/assets/scenes/three-balls.json"

# Found nowhere: exit 2, one line naming every folder looked in, in order.
(cd "$tmp/cwd" && WHISKER_SCENES=$tmp/scenes "$bin" --headless --scene kat --out k.png) 2>"$tmp/kat.err"
code=$?
[ $code -eq 2 ] || fail "--scene kat: exit $code"
data=$(cd "$(dirname "$bin")" && pwd)/assets/scenes
want="kat.json: scene file not found in $tmp/scenes, $tmp/cwd/assets/scenes, $data;"
grep -qF "$want" "$tmp/kat.err" || fail "--scene kat: $(cat "$tmp/kat.err"); expected: $want"
grep -qF "did you mean --scene cat?" "$tmp/kat.err" || fail "--scene kat: no hint"
[ "$(wc -l <"$tmp/kat.err")" -eq 1 ] || fail "--scene kat: not one line"

# The positional FILE: a scene file, an OBJ in the cat's room.
expect from-cwd assets/scenes/three-balls.json
# A tiny triangle far off: as --mesh it is out of sight (the empty room);
# as FILE it is fitted where the cat stands, so the image differs.
printf 'v 5000 0 0\nv 5000.01 0 0\nv 5000 0.008 0\nf 1 2 3\n' >"$tmp/cwd/tri.obj"
expect cat tri.obj --out tri.png
python3 "$here/check_png.py" "$tmp/cwd/tri.png" 512 512 0.5 || fail "tri.png"
expect cat --scene cat --mesh tri.obj --out room.png
cmp -s "$tmp/cwd/tri.png" "$tmp/cwd/room.png" && fail "tri.obj as FILE is not in view"
expect cat --scene cat --mesh tri.obj --out room2.png
cmp -s "$tmp/cwd/room.png" "$tmp/cwd/room2.png" || fail "two renders of one scene differ"
# Refused, exit 2, one line: other files, two scenes, two meshes.
refused() {  # message args...
  local want=$1
  shift
  (cd "$tmp/cwd" && "$bin" --headless --out r.png "$@") 2>"$tmp/r.err"
  local code=$?
  [ $code -eq 2 ] || fail "$*: exit $code, expected 2"
  grep -qF "$want" "$tmp/r.err" || fail "$*: $(cat "$tmp/r.err"); expected: $want"
}
refused "unexpected argument notes.txt (a file to open ends in .json or .obj" notes.txt
refused "tri.obj and --scene cat both name the scene; give one" tri.obj --scene cat
refused "tri.obj and --mesh x.obj both name the mesh; give one" tri.obj --mesh x.obj
refused "unexpected argument b.json" a.json b.json
echo "scene lookup OK"
