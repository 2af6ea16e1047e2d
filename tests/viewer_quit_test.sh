#!/usr/bin/env bash
# Esc and quitting in the real window under Xvfb (xdotool):
#   D. the scene dropdown opened, Esc closes it and the viewer stays; Esc
#      again, with no edits, quits at once (exit 0, nothing asked);
#   E. after an edit (an orbit), Esc asks "Quit and discard the edits?" and
#      the viewer stays; Esc closes the question (the viewer still there);
#      Esc asks again and Enter quits (exit 0).
# Exit 77 (ctest: skipped) without Xvfb or xdotool.
#   viewer_quit_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool

cat >"$dir/drive.sh" <<'INNER'
# The window is 912x800: the image left, the panel right, the Scene
# section's dropdown at (640, 382).
D() { click 640 382; press Escape; sleep 1.5; running && echo "alive after Esc" >>"$dir/D.notes"; }
E() {
  drag 256 400 320 400
  press Escape; sleep 1.5; running && echo "alive after Esc: asked" >>"$dir/E.notes"
  press Escape; sleep 1.5; running && echo "alive after Esc on the question" >>"$dir/E.notes"
}
session D "" D
session E "" E
INNER

in_xvfb
echo "--- D"; cat "$dir/D.err" "$dir/D.notes"; echo "--- E"; cat "$dir/E.err" "$dir/E.notes"
check "D: Esc on the open dropdown closed it and quit nothing" 'grep -q "^alive after Esc$" "$dir/D.notes"'
check "D: the second Esc, with no edits, quit without asking (exit 0)" 'grep -q "^exit 0$" "$dir/D.err" && [ ! -e "$dir/D.asked" ]'
check "D: the dropdown changed nothing (generation 1)" '[ "$(generation D)" = 1 ]'
check "E: after an edit Esc asked instead of quitting" 'grep -q "^alive after Esc: asked$" "$dir/E.notes"'
check "E: Esc on the question closed it and quit nothing" 'grep -q "^alive after Esc on the question$" "$dir/E.notes"'
check "E: asked again, Enter quit with exit 0" '[ -e "$dir/E.asked" ] && grep -q "^exit 0$" "$dir/E.err"'
exit $fail
