#!/usr/bin/env bash
# Save scene leaves nothing to discard, in the real window under Xvfb
# (xdotool), read back from the viewer's event log (--edit-log), its title
# and an X screenshot:
#   three balls: an orbit (a drag on the image), Save scene, then "diffuse-ball"
#   typed into the path field and Enter: it loads at once (no "Discard the
#   edits?": the edits are in the file). There: an orbit, Save scene, and
#   another orbit; loading "three-balls" now asks (the last orbit is in no
#   file): the title still names diffuse-ball and the dialog is on the
#   screen. "Discard and load" loads it. An orbit, Save scene, Esc: the
#   viewer quits at once (closing never asks) with exit 0.
# The saved scene files hold the orbited cameras, under free names.
# Exit 77 (ctest: skipped) without Xvfb, xdotool or xwd.
#   viewer_scene_save_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool xwd python3

cat >"$dir/drive.sh" <<'INNER'
# The 912x800 window with the Save section open: its Save scene button, the
# Scene section's path field; the dialog's button, centred in the window.
SAVE_X=558 SAVE_Y=428 PATH_X=640 PATH_Y=497 DISCARD_X=352 DISCARD_Y=426
title() { xdotool getwindowname "$wid"; }
orbit() { mark; slide 256 400 "$1" 400; wait_image; }
save_scene() { mark; tap $SAVE_X $SAVE_Y; wait_message; }
load() {  # scene name typed into the path field, then Enter
  mark; tap $PATH_X $PATH_Y; hold_key a ctrl; type_in "$1"; hold_key Return
}
wait_title() { for k in $(seq 100); do title | grep -q "$1" && break; sleep 0.1; done; title >>"$dir/S.titles"; }
open_logged S "" || exit 0
tap 640 336  # the Save section
orbit 300; save_scene
load diffuse-ball; wait_message; wait_title diffuse-ball
orbit 300; save_scene; orbit 220
load three-balls
log_wait "len(asks) > 0" 30; move_to 880 790
title >>"$dir/S.titles"; shot asking
mark; tap $DISCARD_X $DISCARD_Y; wait_message; wait_title three-balls
orbit 200; save_scene
quit_viewer S
INNER

in_xvfb

cat >"$dir/asked.py" <<'INNER'
import sys
sys.path.insert(0, sys.argv[1])
from viewer_check import read_xwd
w, h, px = read_xwd(sys.argv[2])
# The dialog's title bar (ImGui's active title colour) at the window's centre.
r, g, b = px[(366 * w + 456) * 3:(366 * w + 456) * 3 + 3]
print(f"at the dialog's title bar: {r}, {g}, {b}")
sys.exit(0 if b > r + 40 and b > 90 and g > r else 1)
INNER
cat >"$dir/camera.py" <<'INNER'
import json, sys
eye = json.load(open(sys.argv[1]))["camera"]["position"]
print(sys.argv[1].rsplit("/", 1)[-1], "eye", eye)
sys.exit(0 if abs(eye[0]) > 0.5 else 1)  # orbited: off the axis the scenes look along
INNER

echo "--- S"; cat "$dir/S.out" "$dir/S.err" "$dir/S.titles"; grep -v '^frame\|^readout\|^edit' "$dir/S.log"; ls "$dir/cwd"
asks() { grep -c '^ask ' "$dir/S.log"; }
check "every wait for the window was met in time" '[ ! -s "$dir/waits.err" ]'
check "S: the viewer quit on Esc with exit 0 (closing after Save scene asks nothing)" 'grep -q "^exit 0$" "$dir/S.err"'
check "S: after Save scene, loading diffuse-ball asked nothing and loaded it" \
  '[ "$(sed -n 1p "$dir/S.titles" | grep -c diffuse-ball)" = 1 ] && grep -q "^message .*text=loaded .*diffuse-ball.json" "$dir/S.log"'
check "S: after a further orbit, loading three-balls asked once (and only then)" \
  '[ "$(asks)" = 1 ] && grep -q "^ask .*load=three-balls$" "$dir/S.log"'
check "S: while it asked, the title still named diffuse-ball" '[ "$(sed -n 2p "$dir/S.titles" | grep -c diffuse-ball)" = 1 ]'
check "S: the dialog was on the screen" '"$py" "$dir/asked.py" "$tests" "$dir/asking.xwd"'
check "S: Discard and load loaded three-balls" '[ "$(sed -n 3p "$dir/S.titles" | grep -c three-balls)" = 1 ]'
check "S: the saved scenes hold the orbited cameras, the second three-balls under a free name" \
  'for f in three-balls-edited diffuse-ball-edited three-balls-edited-2; do "$py" "$dir/camera.py" "$dir/cwd/$f.json" || exit 1; done'
exit $fail
