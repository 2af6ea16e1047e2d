#!/usr/bin/env bash
# Real input through the X server (xdotool) into the viewer under Xvfb:
#   A. clicks on the panel and on the image, and a drag that starts on the
#      panel and ends over the image, restart nothing and leave the camera
#      where it was (ImGui's WantCaptureMouse);
#   B. R restarts, a drag on the image orbits the camera, Esc quits (exit 0).
# The viewer's closing line gives the generation (1 = never restarted); C
# prints the camera. Exit 77 (ctest: skipped) without Xvfb or xdotool.
#   viewer_input_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool

cat >"$dir/drive.sh" <<'EOF'
# The window is 912x800: the image left (512 wide), the panel right; at
# (880, 780) the panel shows nothing but the space right of a label.
A() { click 880 780; click 256 400; drag 880 780 300 400; press c; }
B() { press r; drag 256 400 320 400; press c; }
session A "" A
session B "" B
EOF

in_xvfb
eye_x() { eye "$1" 1 | cut -d' ' -f1; }
echo "--- A"; cat "$dir/A.err"; echo "--- B"; cat "$dir/B.err"
check "A: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/A.err"'
check "A: panel and image clicks and a drag from the panel restarted nothing (generation 1)" '[ "$(generation A)" = 1 ]'
check "A: the camera did not move (eye x = 0)" '[ "$(eye_x A)" = 0.0 ]'
check "B: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/B.err"'
check "B: R and the drag restarted the render (generation >= 3)" '[ "$(generation B)" -ge 3 ]'
check "B: the drag on the image orbited the camera (eye x != 0)" '[ "$(eye_x B)" != 0.0 ]'
exit $fail
