#!/usr/bin/env bash
# Sampling > stop at, in the real window under Xvfb (xdotool), read back
# from the viewer's event log (--edit-log): three balls, anti-aliased (its
# estimate is not exact, so it renders on):
#   3 typed into "s (0: off)": the render stops after 3 s of render time,
#   the panel's state says "stopped: 3.0 s reached"; once the pass in
#   flight has landed, two seconds on it has not taken a sample more. An
#   orbit starts a new render, which renders (more than one pass) and
#   stops again after 3 s.
#   0 typed there: the render goes on. 50 typed into "% noise": it stops
#   once the noise is known, "stopped: noise 50 % reached".
# Exit 77 (ctest: skipped) without Xvfb, xdotool or python3.
#   viewer_stop_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool python3

cat >"$dir/drive.sh" <<'INNER'
# The 912x800 window on three balls: the stop line's two fields.
NOISE_X=605 SECONDS_X=740 STOP_Y=728
type_field() {  # x text: replaces the field's number, then Enter
  tap "$1" $STOP_Y; hold_key a ctrl; type_in "$2"; hold_key Return
}
spp_now() { "$py" -c "import sys; sys.path.insert(0, '$tests'); import viewer_check as v; f = v.log_names(v.read_log('$log'))['f']; print(f['own_gen'], f['own_spp'])"; }
open_logged S "--aa on --target-spp 0" || exit 0
type_field $SECONDS_X 3
log_wait "states[-1] == 'stopped: 3.0 s reached'" 60
sleep 1; after_frames true; spp_now >"$dir/S.first"; sleep 2; after_frames true; spp_now >"$dir/S.later"
mark; slide 256 400 300 400; wait_image
log_wait "len(edits) > $marked and f['own_gen'] == f['gen'] and states[-1] == 'stopped: 3.0 s reached'" 60
spp_now >"$dir/S.second"
type_field $SECONDS_X 0
log_wait "states[-1].startswith('rendering')" 30
type_field $NOISE_X 50
log_wait "states[-1] == 'stopped: noise 50 % reached'" 60
move_to 880 180
quit_viewer S
INNER

in_xvfb

echo "--- S"; cat "$dir/S.err"; grep '^state\|^edit' "$dir/S.log"; echo "first $(cat "$dir/S.first") later $(cat "$dir/S.later") second $(cat "$dir/S.second")"
check "every wait for the window was met in time" '[ ! -s "$dir/waits.err" ]'
check "S: the viewer quit with exit 0" 'grep -q "^exit 0$" "$dir/S.err"'
check "S: after 3 s the panel said stopped: 3.0 s reached" 'grep -q "^state .*text=stopped: 3.0 s reached$" "$dir/S.log"'
check "S: after the pass in flight at the stop, two seconds without a sample more" \
  '[ -n "$(cat "$dir/S.first")" ] && [ "$(cat "$dir/S.first")" = "$(cat "$dir/S.later")" ]'
check "S: after an orbit the new render rendered more than one pass and stopped again" \
  'read g1 n1 <"$dir/S.first"; read g2 n2 <"$dir/S.second"; [ "$g2" -gt "$g1" ] && [ "$n2" -gt 1 ] && [ "$(grep -c "text=stopped: 3.0 s reached$" "$dir/S.log")" -ge 2 ]'
check "S: with the limit off it rendered on" 'grep "^state " "$dir/S.log" | sed -n "/stopped: 3.0 s/,\$p" | grep -q "text=rendering"'
check "S: 50 % noise: stopped: noise 50 % reached" 'grep -q "^state .*text=stopped: noise 50 % reached$" "$dir/S.log"'
exit $fail
