#!/usr/bin/env bash
# Save in the A/B wipe writes what the window shows, in the real window under
# Xvfb (xdotool). Three balls with anti-aliasing, 2 spp (the render stops
# there, so the screen stands still):
#   S saves the live image (A); "Hold this image" (Compare) holds it and
#   turns the wipe on; Fresnel on (an edit: the glass balls change) renders
#   again to 2 spp; an X screenshot of the window; S saves the wipe (W).
# Checks: W left of the wipe line is A to the byte (the held image); right of
# it W differs from A (the live render); W is the screenshot's image area to
# one level (the wipe line and its labels, drawn over the screen only, left
# out); the panel's message says "as shown: held left, live right" and ends
# with the folder it saved into, by its full path.
# Exit 77 (ctest: skipped) without Xvfb, xdotool or xwd.
#   viewer_wipe_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool xwd python3

cat >"$dir/drive.sh" <<'INNER'
open_logged W "--aa on --target-spp 2" || exit 0
done2() { log_wait "len(edits) > $marked and f['own_gen'] == f['gen'] == f['shown_gen'] and f['own_spp'] >= 2"; }
marked=0 && done2
move_to 880 790  # the pointer on an empty part of the panel
mark; hold_key s; wait_message
# The 912x800 window: the panel's Compare header, then (opened) its Hold
# button; the sections below move down by the Compare lines.
tap 640 313; tap 576 336
mark; tap 714 589; wait_image; done2  # Fresnel on
move_to 880 790
shot W
mark; hold_key s; wait_message
quit_viewer W
INNER

in_xvfb

cat >"$dir/compare.py" <<'INNER'
import os, sys
sys.path.insert(0, sys.argv[1])
from viewer_check import crop, log_names, read_log, read_png, read_xwd
d = sys.argv[2]
names = log_names(read_log(f"{d}/W.log"))
area = names["f"]["area"]
w, h, a = read_png(f"{d}/cwd/three-balls-2spp.png")
_, _, wipe = read_png(f"{d}/cwd/three-balls-2spp-2.png")
_, _, screen = crop(read_xwd(f"{d}/W.xwd"), *area)
cols = round(0.5 * w)  # the wipe slider's default, whole image columns
what = sys.argv[3]
if what == "left":
    same = all(wipe[(y * w) * 3:(y * w + cols) * 3] == a[(y * w) * 3:(y * w + cols) * 3] for y in range(h))
    print(f"left of column {cols}: {'the held image to the byte' if same else 'NOT the held image'}")
    sys.exit(0 if same else 1)
if what == "right":
    changed = sum(1 for y in range(h) for k in range((y * w + cols) * 3, (y * w + w) * 3)
                  if abs(wipe[k] - a[k]) > 8)
    print(f"right of column {cols}: {changed} channels differ from the held image by more than 8 levels")
    sys.exit(0 if changed > 2000 else 1)
# The screen: the wipe line (2 px wide at the line) and its "held" / "live"
# labels (top rows beside it) are drawn over the image on the screen only.
def overlay(x, y):
    return abs(x - cols) <= 3 or (abs(x - cols) <= 60 and y < 30)
off = big = n = 0
for y in range(h):
    for x in range(w):
        if overlay(x, y):
            continue
        for c in range(3):
            e = abs(wipe[(y * w + x) * 3 + c] - screen[(y * w + x) * 3 + c])
            n += 1
            off += e != 0
            big += e > 1
print(f"saved against the screen: {off} of {n} channels differ, {big} by more than one level")
sys.exit(0 if big == 0 and off <= n * 1e-4 else 1)
INNER

echo "--- W"; cat "$dir/W.out" "$dir/W.err"; grep -v '^frame\|^readout' "$dir/W.log"; ls "$dir/cwd"
check "every wait for the window was met in time" '[ ! -s "$dir/waits.err" ]'
check "W: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/W.err"'
check "W: both saves were written" '[ -f "$dir/cwd/three-balls-2spp.png" ] && [ -f "$dir/cwd/three-balls-2spp-2.png" ]'
check "W: left of the wipe line the save is the held image" '"$py" "$dir/compare.py" "$tests" "$dir" left'
check "W: right of it the save is the live render (Fresnel on changed it)" '"$py" "$dir/compare.py" "$tests" "$dir" right'
check "W: the save is the screen's image area (to one level)" '"$py" "$dir/compare.py" "$tests" "$dir" screen'
folder=$(cd "$dir/cwd" && pwd -P)
check "W: the message says the save is the wipe as shown and names the folder ($folder)" \
  'grep -q "^message .*text=saved three-balls-2spp-2.png (as shown: held left, live right) .*, in $folder\$" "$dir/W.log"'
exit $fail
