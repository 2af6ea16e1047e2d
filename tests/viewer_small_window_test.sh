#!/usr/bin/env bash
# A small window, the pixel readout and tooltips, in the real window under
# Xvfb (xdotool), read back from the viewer's event log (--edit-log) and X
# screenshots (three balls, 512x512):
#   U. the pointer rests on the light's position field when the window
#      opens: no tooltip in its first three seconds. Moved onto Restart, its
#      tooltip waits (none three frames later), then shows. A drag of the
#      light's intensity field resting on it, and a drag from the image onto
#      Restart held there: no tooltip while the button is down.
#   R. the readout near the image's centre (in each quarter) never covers
#      the centre; I hides it (no readout while the pointer moves over the
#      image), I shows it again.
#   W. 700x400: the panel narrows to 300, the image is 400x400. 400x300: the
#      panel steps aside, the image is 300x300 in the middle of the window
#      and the screenshot shows it there, the panel nowhere. Tab: the panel
#      over the image's right part, the image still 300x300. Tab: hidden
#      again; back at 912x800 it stays hidden (asked for), and Tab puts it
#      beside the 512x512 image.
# Exit 77 (ctest: skipped) without Xvfb, xdotool or xwd.
#   viewer_small_window_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool xwd python3

cat >"$dir/drive.sh" <<'INNER'
# The 912x800 window: the light's position and intensity fields, the
# Restart button.
LIGHT_X=600 LIGHT_Y=451 POWER_X=645 POWER_Y=474 RESTART_X=667 RESTART_Y=202
count() { grep -c "^$1 " "$log"; }
resize() {  # w h: waits for the frame whose image area is given next
  xdotool windowsize "$wid" "$1" "$2"
  log_wait "f['area'] == [$3, $4, $5, $6]" 30
}
U() {
  xdotool mousemove $LIGHT_X $LIGHT_Y  # the window opens at 0, 0 under it
  open_logged U "" || return
  log_wait "f['t'] >= 3" 30  # three seconds of frames (the panel's clock draws them)
  grep -c '^tip .*text=.' "$log" >"$dir/U.startup"
  n=$(count tip)
  after_frames xdotool mousemove --window "$wid" $RESTART_X $RESTART_Y
  [ "$(grep '^tip ' "$log" | tail -n +$((n + 1)) | grep -c 'text=.')" = 0 ] && echo none >"$dir/U.early"
  log_wait "tips and tips[-1].startswith('Throw the samples away')" 20
  # A drag of the light's intensity, resting on the field with the button
  # held; then a drag from the image onto Restart, resting there.
  move_to $POWER_X $POWER_Y; after_frames xdotool mousedown 1
  for k in 1 2 3; do after_frames xdotool mousemove --window "$wid" $(( POWER_X + 8 * k )) $POWER_Y; done
  sleep 1.5; after_frames true
  grep '^tip ' "$log" | tail -1 >"$dir/U.held"  # the tooltip shown now
  after_frames xdotool mouseup 1
  move_to 256 500; after_frames xdotool mousedown 1
  for k in 1 2 3; do after_frames xdotool mousemove --window "$wid" $(( 256 + (RESTART_X - 256) * k / 3 )) $(( 500 + (RESTART_Y - 500) * k / 3 )); done
  sleep 1.5; after_frames true
  grep '^tip ' "$log" | tail -1 >>"$dir/U.held"
  after_frames xdotool mouseup 1
  quit_viewer U
}
R() {
  open_logged R "" || return
  local x y
  for xy in "276 420" "236 420" "276 380" "236 380"; do
    set -- $xy
    n=$(count readout)
    after_frames xdotool mousemove --window "$wid" "$1" "$2"
    log_wait "len(readouts) > $n and readouts[-1]['lines'][0].startswith('pixel (%d, %d)' % ($1, $2 - 144))" 30
  done
  hold_key i
  n=$(count readout)
  for x in 300 320 340; do after_frames xdotool mousemove --window "$wid" $x 450; done
  after_frames true
  echo $(( $(count readout) - n )) >"$dir/R.hidden"
  hold_key i
  after_frames xdotool mousemove --window "$wid" 360 450
  log_wait "len(readouts) > $n and readouts[-1]['lines'][0].startswith('pixel (360, 306)')" 30
  quit_viewer R
}
W() {
  open_logged W "" || return
  xdotool mousemove 1200 700  # off the window: no readout in the screenshots
  resize 700 400 0 0 400 400
  resize 400 300 50 0 300 300
  sleep 0.5; after_frames true; shot W-hidden
  hold_key Tab; log_wait "panels[-1]['visible'] == 1 and panels[-1]['overlay'] == 1" 20
  sleep 0.5; after_frames true; shot W-over
  hold_key Tab; log_wait "panels[-1]['visible'] == 0" 20
  resize 912 800 200 144 512 512
  hold_key Tab; log_wait "panels[-1]['visible'] == 1 and f['area'] == [0, 144, 512, 512]" 20
  quit_viewer W
}
U; R; W
INNER

in_xvfb 400

cat >"$dir/small.py" <<'INNER'
import sys
sys.path.insert(0, sys.argv[1])
from viewer_check import crop, image_stats, log_names, read_log, read_xwd, sane
d, what = sys.argv[2], sys.argv[3]
if what == "readout":  # every readout box leaves the image's centre (256, 400) uncovered
    rs = log_names(read_log(f"{d}/R.log"))["readouts"]
    bad = [r for r in rs if r["box"][0] <= 256 < r["box"][0] + r["box"][2] and r["box"][1] <= 400 < r["box"][1] + r["box"][3]]
    for r in rs:
        print("  box", r["box"], r["lines"][0])
    sys.exit(0 if rs and not bad else 1)
if what == "panels":  # the panel lines of W: beside at 400, at 300, hidden, over, hidden, beside
    ps = log_names(read_log(f"{d}/W.log"))["panels"]
    seq = [(p["visible"], p["overlay"], p["width"]) for p in ps]
    print(seq)
    want = [(1, 0, 400.0), (1, 0, 300.0), (0, 0, 0.0), (1, 1, 280.0), (0, 0, 0.0), (1, 0, 400.0)]
    sys.exit(0 if seq == want else 1)
hidden, over = read_xwd(f"{d}/W-hidden.xwd"), read_xwd(f"{d}/W-over.xwd")
if what == "hidden":  # the image in the middle, the window's background beside it
    ok, stats = sane(crop(hidden, 50, 0, 300, 300))
    side = image_stats(crop(hidden, 356, 40, 40, 250))
    print("image", stats, "right of it", side)
    sys.exit(0 if ok and side["colours"] <= 2 and side["mean"] < 40 else 1)
if what == "over":  # the panel covers the right, the image's left part unchanged
    def diff(x, y, w, h):
        a, b = crop(hidden, x, y, w, h)[2], crop(over, x, y, w, h)[2]
        return sum(abs(p - q) for p, q in zip(a, b)) / len(a)
    left, right = diff(52, 40, 60, 250), diff(130, 0, 260, 300)
    print(f"mean difference: image left of the panel {left:.1f}, under the panel {right:.1f}")
    sys.exit(0 if left < 10 and right > 15 else 1)
INNER

p() { "$py" "$dir/small.py" "$tests" "$dir" "$@"; }
for s in U R W; do echo "--- $s"; cat "$dir/$s.err"; grep -v '^frame\|^readout' "$dir/$s.log" | head -40; done
check "every wait for the window was met in time" '[ ! -s "$dir/waits.err" ]'
check "U: no tooltip in the first three seconds under a pointer that had not moved" '[ "$(cat "$dir/U.startup")" = 0 ]'
check "U: moved onto Restart, no tooltip three frames later" '[ "$(cat "$dir/U.early" 2>/dev/null)" = none ]'
check "U: then the Restart tooltip" 'grep -q "^tip .*text=Throw the samples away" "$dir/U.log"'
check "U: no tooltip while a drag holds the button on the light's intensity or over Restart" \
  '[ "$(wc -l <"$dir/U.held")" = 2 ] && ! grep -q "text=." "$dir/U.held"'
check "U, R, W: the viewer quit with exit 0" 'for s in U R W; do grep -q "^exit 0$" "$dir/$s.err" || exit 1; done'
check "R: no readout box covers the image's centre" 'p readout'
check "R: with I no readout while the pointer moves over the image" '[ "$(cat "$dir/R.hidden")" = 0 ]'
check "W: the panel beside at 400, 300 wide at 700x400, hidden at 400x300, over the image with Tab, hidden, beside again" 'p panels'
check "W: at 400x300 the screenshot shows the image in the middle and no panel" 'p hidden'
check "W: with Tab the panel covers the image's right part, its left part unchanged" 'p over'
exit $fail
