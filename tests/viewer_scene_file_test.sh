#!/usr/bin/env bash
# The Scene dropdown and the saved float file's header, in the real window
# under Xvfb (xdotool), read back from the viewer's event log (--edit-log)
# and the files it writes:
#   the cat: "glass mesh" clicked, S after the first full pass of the glass
#   cat: the EXR header's objects give the mesh glass, its edits (a JSON
#   Patch from the scene as loaded) change the mesh's material to glass,
#   and it carries the display exposure that maps its scene units to the
#   report's white (log2 of 1/255^2.2) with the note on half floats. Save
#   scene, then cat-edited.json typed into the path field: the dropdown says
#   "file: cat-edited.json" (the file's scene is still named cat); then
#   three-balls typed there: the dropdown says three-balls.
# Exit 77 (ctest: skipped) without Xvfb, xdotool or python3.
#   viewer_scene_file_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool python3

cat >"$dir/drive.sh" <<'INNER'
# The 912x800 window on the cat: the glass mesh box; with the Save section
# open, its Save scene button and the Scene section's path field.
GLASS_X=527 GLASS_Y=636 SAVE_HEADER_X=640 SAVE_HEADER_Y=336 SAVE_X=558 SAVE_Y=428 PATH_X=640 PATH_Y=497
load() {  # a scene typed into the path field, then Enter
  mark; tap $PATH_X $PATH_Y; hold_key a ctrl; type_in "$1"; hold_key Return; wait_message
}
open_logged F "--scene cat" || exit 0
mark; tap $GLASS_X $GLASS_Y; wait_image
log_wait "f['own_gen'] == f['gen'] and f['own_spp'] >= 1 and f['shown_own'] >= 1" 90
mark; hold_key s; wait_message
tap $SAVE_HEADER_X $SAVE_HEADER_Y
mark; tap $SAVE_X $SAVE_Y; wait_message
load cat-edited.json; log_wait "scenes[-1] == 'file: cat-edited.json'" 30
load three-balls; log_wait "scenes[-1] == 'three-balls'" 30
move_to 880 790
quit_viewer F
INNER

in_xvfb

cat >"$dir/header.py" <<'INNER'
import glob, json, math, struct, sys
# The string attributes of an OpenEXR header: name, type, size, value.
files = glob.glob(sys.argv[1] + "/cat-*spp.exr")
if len(files) != 1:
    print("EXR files:", files); sys.exit(1)
data = open(files[0], "rb").read()
assert data[:4] == b"\x76\x2f\x31\x01", "not an OpenEXR file"
pos, attrs = 8, {}
while data[pos] != 0:
    name_end = data.index(b"\0", pos); name = data[pos:name_end].decode()
    type_end = data.index(b"\0", name_end + 1); kind = data[name_end + 1:type_end].decode()
    size = struct.unpack("<i", data[type_end + 1:type_end + 5])[0]
    value = data[type_end + 5:type_end + 5 + size]
    if kind == "string":
        attrs[name] = value.decode("utf-8", "replace")
    pos = type_end + 5 + size
what = sys.argv[2]
for k in sorted(attrs):
    if k.startswith("whisker.") and what == "objects":
        print(f"  {k}: {attrs[k][:160]}")
if what == "objects":
    meshes = json.loads(attrs["whisker.objects"])["meshes"]
    sys.exit(0 if meshes and all(m["material"]["type"] == "glass" for m in meshes) else 1)
if what == "edits":
    ops = json.loads(attrs["whisker.edits"])
    glass = [op for op in ops if op["path"].startswith("/meshes/0/material") and op.get("value") == "glass"]
    sys.exit(0 if glass else 1)
if what == "exposure":
    want = math.log2(255.0 ** -2.2)
    got = float(attrs["whisker.display_exposure"])
    scale = float(attrs["whisker.display_scale"])
    print(f"display exposure {got} (want {want:.4f}), scale {scale}")
    ok = abs(got - want) < 1e-3 and abs(scale / 2.0 ** want - 1) < 1e-4
    ok = ok and "65504" in attrs["whisker.display_note"] and attrs["whisker.units"].startswith("scene")
    sys.exit(0 if ok else 1)
INNER

echo "--- F"; cat "$dir/F.out" "$dir/F.err"; grep -v '^frame\|^readout\|^tip' "$dir/F.log"; ls "$dir/cwd"
h() { "$py" "$dir/header.py" "$dir/cwd" "$@"; }
check "every wait for the window was met in time" '[ ! -s "$dir/waits.err" ]'
check "F: the viewer quit with exit 0" 'grep -q "^exit 0$" "$dir/F.err"'
check "F: the EXR header's objects give the cat's mesh glass" 'h objects'
check "F: the EXR header's edits change the mesh's material to glass" 'h edits'
check "F: the EXR header gives the exposure from scene units to the report's white, and the half-float note" 'h exposure'
check "F: the dropdown said cat at first" 'grep -q "^scene .*text=cat$" "$dir/F.log"'
check "F: after loading the saved scene file the dropdown says file: cat-edited.json" \
  'grep -q "^message .*text=loaded .*cat-edited.json" "$dir/F.log" && grep -q "^scene .*text=file: cat-edited.json$" "$dir/F.log"'
check "F: after loading three-balls the dropdown says three-balls" \
  '[ "$(grep "^scene " "$dir/F.log" | tail -1 | sed "s/.*text=//")" = three-balls ]'
exit $fail
