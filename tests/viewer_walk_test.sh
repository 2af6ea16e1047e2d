#!/usr/bin/env bash
# What a new user does on the cat, in the real window under Xvfb (xdotool):
# start; orbit with a drag; wheel in 3 notches, then out 8 (the camera stops
# at the wall); move the light with the panel (a drag on its x); glass mesh,
# Fresnel on, indirect light off; max depth down; undo, redo; S; Esc.
# Every step but the save waits for the window to show a new render (a new
# generation, from the viewer's event log). After every step: the window is
# there and answers, and its X screenshot's image area is a sane render (not
# black, many colours). Throughout, from the viewer's event log: no
# NaN/Inf sample, the eye never outside the room, the title's spp the
# panel's in every frame; every edit a new render (generation). At the end
# the saved PNG is a sane render too and Esc quits with exit 0.
# Exit 77 (ctest: skipped) without Xvfb, xdotool or xwd.
#   viewer_walk_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool xwd python3

cat >"$dir/drive.sh" <<'INNER'
# After a step: the pointer off the image (no readout over it), a
# screenshot, and whether the window still answers.
step() {
  move_to 880 790
  shot "$1"
  if alive; then echo "$1" >>"$dir/steps"; else echo "$1: the window is gone" >>"$dir/steps"; fi
}
edit() { mark; "$@"; wait_image; }  # an action that must show a new render
open_logged K "--scene cat" || exit 0
step 0-start
edit slide 200 400 260 380; step 1-orbit
edit roll 256 400 3; step 2-wheel-in
edit roll 256 400 -8; step 3-wheel-out
# The panel of the cat (912x800 window): the light's x, the sampling section.
edit slide 540 451 580 451; step 4-light
edit tap 529 635; step 5-glass
edit tap 721 520; step 6-fresnel
edit tap 529 520; step 7-indirect-off
edit tap 560 589; step 8-depth
edit hold_key z ctrl; step 9-undo
edit hold_key y ctrl; step 10-redo
mark; hold_key s; wait_message; step 11-save
quit_viewer K
INNER

in_xvfb

cat >"$dir/walk.py" <<'INNER'
import glob, os, sys
sys.path.insert(0, sys.argv[1])
from viewer_check import crop, log_names, read_log, read_png, read_xwd, sane
d = sys.argv[2]
names = log_names(read_log(f"{d}/K.log"))
area = names["f"]["area"]
what = sys.argv[3]
if what == "images":  # every step's image area a sane render
    steps = [s for s in open(f"{d}/steps").read().split() if "gone" not in s]
    ok = True
    for s in steps:
        good, st = sane(crop(read_xwd(f"{d}/{s}.xwd"), *area))
        print(f"{s}: mean {st['mean']:.1f}, black {100 * st['black']:.1f} %, {st['colours']} colours"
              f"{'' if good else ' -- NOT SANE'}")
        ok = ok and good
    sys.exit(0 if ok and len(steps) == 12 else 1)
if what == "steady":  # ticking glass mesh moved nothing below its row
    a, b = read_xwd(f"{d}/4-light.xwd"), read_xwd(f"{d}/5-glass.xwd")
    x0 = area[0] + area[2] + 4
    rows = [y for y in range(649, 780) if crop(a, x0, y, 70, 1)[2] != crop(b, x0, y, 70, 1)[2]]
    print(f"rows of the panel's left strip below the glass mesh row that differ: {len(rows)}")
    sys.exit(0 if not rows else 1)
if what == "log":
    fs = names["frames"]
    nan = max(f["nan"] for f in fs)
    differ = sum(1 for f in fs if f["title_spp"] != f["panel_spp"])
    out = [t for t in names["outside"] if t]
    print(f"{len(fs)} frames, {len(names['edits'])} generations; NaN/Inf dropped at most {nan}; "
          f"{differ} frames where the title and the panel differ; outside the room: {out or 'never'}")
    sys.exit(0 if nan == 0 and differ == 0 and not out else 1)
if what == "saved":
    pngs = glob.glob(f"{d}/cwd/cat-*spp.png")
    good, st = sane(read_png(pngs[0])) if len(pngs) == 1 else (False, {})
    print(pngs, st)
    sys.exit(0 if good else 1)
INNER

echo "--- K"; cat "$dir/K.out" "$dir/K.err" "$dir/steps"; grep -v '^frame\|^readout\|^edit' "$dir/K.log"; ls "$dir/cwd"
walk() { "$py" "$dir/walk.py" "$tests" "$dir" "$1"; }
check "K: the window answered after each of the 12 steps" '[ "$(grep -c . "$dir/steps")" = 12 ] && ! grep -q gone "$dir/steps"'
check "K: each step showed in time (no wait timed out)" '[ ! -s "$dir/waits.err" ]'
check "K: after each step the image is a sane render" 'walk images'
check "K: ticking glass mesh moved nothing in the panel below it" 'walk steady'
check "K: wheeling out, the camera stopped at the wall" 'grep -q "^message .*text=the camera stopped at a surface$" "$dir/K.log"'
check "K: no NaN/Inf, the eye always in the room, title and panel agree in every frame" 'walk log'
check "K: every step but the save made a new render (generation >= 11)" '[ "$(generation K)" -ge 11 ]'
check "K: S saved a sane PNG" 'walk saved'
check "K: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/K.err"'
exit $fail
