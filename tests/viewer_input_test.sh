#!/usr/bin/env bash
# Real input through the X server (xdotool) into the viewer under Xvfb:
#   A. clicks on the panel and on the image, and a drag that starts on the
#      panel and ends over the image, restart nothing and leave the camera
#      where it was (ImGui's WantCaptureMouse);
#   B. R restarts, a drag on the image orbits the camera, Esc quits (exit 0);
#   F, G. the same 40-unit drag, its press read in one frame with a pointer
#      move of 800 units (F: the viewer stopped while both arrive) or after
#      the pointer came to rest (G): the same eye, as a drag starts where the
#      button went down.
# The viewer's closing line gives the generation (1 = never restarted); C
# prints the camera. Exit 77 (ctest: skipped) without Xvfb or xdotool.
#   viewer_input_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool

cat >"$dir/drive.sh" <<'EOF'
# The window is 912x800: the image left (512 wide), the panel right; at
# (880, 180) the panel shows nothing but the space right of a status line.
A() { click 880 180; click 256 400; drag 880 180 300 400; press c; }
B() { press r; drag 256 400 320 400; press c; }
F() {
  xdotool mousemove --window "$wid" 880 180; sleep 0.5
  # Stopped, the viewer reads the move and the press in one frame.
  kill -STOP "$pid"; xdotool mousemove --window "$wid" 200 400 mousedown 1; sleep 0.2; kill -CONT "$pid"
  sleep 0.3
  xdotool mousemove --window "$wid" 240 400; sleep 0.3; xdotool mouseup 1; sleep 0.5; press c
}
G() {
  xdotool mousemove --window "$wid" 200 400; sleep 0.5
  xdotool mousedown 1; sleep 0.3
  xdotool mousemove --window "$wid" 240 400; sleep 0.3; xdotool mouseup 1; sleep 0.5; press c
}
session A "" A
session B "" B
session F "" F
session G "" G
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
check "F, G: the drag orbited (eye x != 0)" '[ "$(eye_x G)" != 0.0 ] && [ "$(eye_x G)" != none ]'
check "F, G: a press with a pointer move gives the drag of a press at rest ($(eye F 1) / $(eye G 1))" '[ "$(eye F 1)" = "$(eye G 1)" ]'
exit $fail
