#!/usr/bin/env bash
# The camera stays in the room, and quick key presses are not lost, in the
# real window under Xvfb (xdotool):
#   W. five wheel notches out over the image of the three balls (the eye at
#      z = 55, the wall behind it at z = 60): C prints the camera, whose eye
#      must still be in front of the wall (z < 60);
#   K. C pressed 12 times 5 ms apart (each press released at once, so
#      several fall between two frames): 12 more cameras printed, one a
#      frame (a press is never merged with another or lost).
# Exit 77 (ctest: skipped) without xvfb-run or xdotool.
#   viewer_room_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" xvfb-run xdotool python3

cat >"$dir/drive.sh" <<'INNER'
#!/usr/bin/env bash
bin=$1 dir=$2
. "$3"
W() { xdotool mousemove --window "$wid" 256 300; sleep 0.3
      for k in 1 2 3 4 5; do xdotool click --window "$wid" 5; sleep 0.4; done
      sleep 1; press c
      xdotool key --window "$wid" --delay 5 c c c c c c c c c c c c; sleep 1.5; }
session W "" W
INNER

timeout 300 xvfb-run -a -s "-screen 0 1280x800x24" bash "$dir/drive.sh" "$bin" "$dir" "$(dirname "$0")/viewer_drive.sh"

fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAILED: $1"; fail=1; fi; }
cameras() {  # the eyes' z printed by C, one a line
  python3 - "$dir/W.out" <<'PY'
import json, sys
text, pos, dec = open(sys.argv[1]).read(), 0, json.JSONDecoder()
while True:
    start = text.find("{", pos)
    if start < 0: break
    obj, pos = dec.raw_decode(text, start)
    print(obj["camera"]["position"][2])
PY
}
echo "--- W"; cat "$dir/W.err"; echo "cameras printed: $(cameras | wc -l)"
check "W: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/W.err"'
check "W: after five notches out the eye is in front of the wall (55 < z < 60)" \
  'z=$(cameras | head -1); python3 -c "import sys; sys.exit(0 if 55 < float(\"$z\") < 60 else 1)"'
check "K: every one of 13 C presses printed the camera" '[ "$(cameras | wc -l)" = 13 ]'
exit $fail
