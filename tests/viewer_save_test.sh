#!/usr/bin/env bash
# Save writes what the window shows, and never overwrites: in the real
# window under Xvfb (xdotool) the exposure is set to -2 stops by typing into
# its slider, then S is pressed twice. The first PNG must be the headless
# render (the report's mapping) darkened by 2 stops, (L/4)^(1/2.2), to one
# level; the second must get a free name (-2) and the panel's message says so.
# Exit 77 (ctest: skipped) without Xvfb or xdotool.
#   viewer_save_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool python3

cat >"$dir/drive.sh" <<'INNER'
open_viewer E "--frames 2" || exit 0
wait_spp 2  # the title carries the samples per pixel: both passes done
sleep 1
# Open the Display section (collapsed at first), then Ctrl+click turns the
# exposure slider (912x800 window, panel right) into a text field.
click 640 290
xdotool mousemove --window "$wid" 640 313; sleep 0.2
xdotool keydown ctrl; xdotool mousedown 1; sleep 0.3; xdotool mouseup 1; xdotool keyup ctrl; sleep 0.5
xdotool keydown ctrl; sleep 0.2; xdotool key a; sleep 0.3; xdotool keyup ctrl; xdotool type --delay 150 -- "-2"; sleep 0.3; press Return
xdotool mousemove --window "$wid" 900 790; sleep 0.5
press s
press s
quit_viewer E
INNER

in_xvfb
"$bin" --headless --scene three-balls --frames 2 --threads 1 --quiet --out "$dir/ref.png" >/dev/null 2>&1

cat >"$dir/compare.py" <<'INNER'
# Compares the saved image with the reference darkened by 2 stops.
import sys
sys.path.insert(0, sys.argv[3])
from viewer_check import read_png

w, h, saved = read_png(sys.argv[1])
rw, rh, ref = read_png(sys.argv[2])
assert (w, h) == (rw, rh), "sizes differ"
# ref = floor(L^(1/2.2)); saved should be floor((L/4)^(1/2.2)) = ref * 4^(-1/2.2) within a level.
k = 4 ** (-1 / 2.2)
bad = sum(1 for s, r in zip(saved, ref) if r < 255 and abs(s - r * k) > 1.5)
bright = sum(1 for s in saved if s > 0)
print(f"{bad} of {len(saved)} values off; {bright} non-zero")
sys.exit(0 if bad == 0 and bright > len(saved) // 4 else 1)
INNER

echo "--- E"; cat "$dir/E.out" "$dir/E.err"; ls "$dir/cwd"
check "E: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/E.err"'
check "E: the first save is the image at -2 stops" '"$py" "$dir/compare.py" "$dir/cwd/three-balls-2spp.png" "$dir/ref.png" "$tests"'
check "E: the second save took a free name and said so" \
  '[ -f "$dir/cwd/three-balls-2spp-2.png" ] && grep -q "three-balls-2spp was taken, so the name is three-balls-2spp-2" "$dir/E.out"'
exit $fail
