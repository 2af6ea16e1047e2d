#!/usr/bin/env bash
# The camera stays in the room, and quick key presses are not lost, in the
# real window under Xvfb (xdotool):
#   W. five wheel notches out over the image of the three balls (the eye at
#      z = 55, the wall behind it at z = 60): C prints the camera, whose eye
#      must still be in front of the wall (z < 60);
#   K. C pressed 12 times 5 ms apart (each press released at once, so
#      several fall between two frames): 12 more cameras printed, one a
#      frame (a press is never merged with another or lost).
# Exit 77 (ctest: skipped) without Xvfb or xdotool.
#   viewer_room_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool python3

cat >"$dir/drive.sh" <<'INNER'
W() { xdotool mousemove --window "$wid" 256 300; sleep 0.3
      for k in 1 2 3 4 5; do xdotool click --window "$wid" 5; sleep 0.4; done
      sleep 1; press c
      xdotool key --window "$wid" --delay 5 c c c c c c c c c c c c; sleep 1.5; }
session W "" W
INNER

in_xvfb
cameras() { "$py" "$tests/viewer_check.py" cameras "$dir/W.out" | cut -d' ' -f3; }  # the eyes' z printed by C
echo "--- W"; cat "$dir/W.err"; echo "cameras printed: $(cameras | wc -l)"
check "W: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/W.err"'
check "W: after five notches out the eye is in front of the wall (55 < z < 60)" \
  'z=$(cameras | head -1); "$py" -c "import sys; sys.exit(0 if 55 < float(\"$z\") < 60 else 1)"'
check "K: every one of 13 C presses printed the camera" '[ "$(cameras | wc -l)" = 13 ]'
exit $fail
