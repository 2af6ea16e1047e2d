#!/usr/bin/env bash
# Typing into the panel's fields through the X server (xdotool) under Xvfb:
#   C. typing "nosuch2" into the scene path field saves nothing (the S in it
#      is text, not the Save shortcut) and restarts nothing;
#   U. a drag on the image orbits the camera; Ctrl+Z puts it back (the whole
#      drag is one step) and Ctrl+Y orbits it again;
#   D. `--frames 2` without --screenshot keeps the window open once the two
#      passes are done; typing 15 into "target spp" applies once, on Enter
#      (not 1 and then 15), and raising the target carries the accumulation
#      on in the same generation up to 15 samples per pixel;
#   R. typed past their ranges (Ctrl+click on a slider), max depth -5 and
#      samples/pass 0 are kept at the command line's bounds, 0 and 1, and
#      the panel says what was typed and kept.
# Exit 77 (ctest: skipped) without Xvfb or xdotool.
#   viewer_typing_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool

cat >"$dir/drive.sh" <<'INNER'
. "$dir/layout.sh"
C() { click $PATH_X $PATH_Y; combo a; typed nosuch2; press Return; }
D() { sleep 2; echo "alive after 2 passes" >"$dir/D.alive"; click $TARGET_X $TARGET_Y; combo a;
      typed 15; sleep 2; press Return
      wait_spp 15; }  # the title carries the samples per pixel (a busy machine too)
U() { xdotool mousemove --window "$wid" 256 400; sleep 0.2; xdotool mousedown 1; sleep 0.2
      for k in 1 2 3 4 5 6; do xdotool mousemove --window "$wid" $((256 + 10 * k)) 400; sleep 0.1; done
      xdotool mouseup 1; sleep 0.5; combo z; press c; combo y; press c; }
ctrl_click() { xdotool keydown ctrl; sleep 0.2; click "$1" "$2"; xdotool keyup ctrl; sleep 0.3; }
R() { ctrl_click $DEPTH_X $DEPTH_Y; combo a; typed -5; press Return; sleep 1
      ctrl_click $SPP_X $SPP_Y; combo a; typed 0; press Return; sleep 1; }
session R "--edit-log $dir/R.log" R
session C "" C
session D "--frames 2" D
session U "" U
INNER

# Where the fields are in the 912x800 window (image 512 wide, panel right).
cat >"$dir/layout.sh" <<'INNER'
PATH_X=640 PATH_Y=405
TARGET_X=620 TARGET_Y=681
DEPTH_X=640 DEPTH_Y=589 SPP_X=640 SPP_Y=612
INNER

in_xvfb

field() { sed -n "s/.*generation \([0-9]*\), [0-9]* passes, \([0-9]*\) spp.*/\\$2/p" "$dir/$1.err"; }
echo "--- C"; cat "$dir/C.out" "$dir/C.err"; echo "--- D"; cat "$dir/D.out" "$dir/D.err"
check "C: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/C.err"'
check "C: typing an s into a field saved nothing" '! grep -q "^saved" "$dir/C.out" && [ -z "$(ls "$dir/cwd")" ]'
check "C: typing restarted nothing (generation 1)" '[ "$(field C 1)" = 1 ]'
check "D: the window stayed open after --frames 2" '[ -f "$dir/D.alive" ] && grep -q "^exit 0$" "$dir/D.err"'
check "D: typing 15 and Enter raised the target without a restart (generation 1)" '[ "$(field D 1)" = 1 ]'
check "D: the accumulation went on to 15 spp" '[ "$(field D 2)" = 15 ]'
echo "--- R"; grep "^message" "$dir/R.log"
check "R: max depth -5 kept at 0, and said so" 'grep -q "text=max depth: must be in \[0, 1000\], got -5; kept 0$" "$dir/R.log"'
check "R: samples/pass 0 kept at 1, and said so" 'grep -q "text=samples/pass: must be in \[1, 65536\], got 0; kept 1$" "$dir/R.log"'
check "R: the viewer quit with exit 0" 'grep -q "^exit 0$" "$dir/R.err"'
eye_x() { eye "$1" "$2" | cut -d' ' -f1; }  # the camera printed by the n-th C press
echo "--- U"; cat "$dir/U.err"; grep -A2 position "$dir/U.out"
check "U: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/U.err"'
check "U: Ctrl+Z put the orbited camera back (eye x = 0)" '[ "$(eye_x U 1)" = 0.0 ]'
check "U: Ctrl+Y orbited it again (eye x != 0)" 'x=$(eye_x U 2); [ "$x" != 0.0 ] && [ "$x" != none ]'
exit $fail
