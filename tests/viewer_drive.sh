# The viewer tests' shared shell (viewer_*_test.sh). A test script sources
# it and runs in two halves:
#
#   outside the X server:  viewer_test_setup BINARY tools...   ($bin, $dir, $tests)
#                          write the actions into "$dir/drive.sh"
#                          in_xvfb [SECONDS]                    (runs them in Xvfb)
#                          check "what" 'shell condition'  ...  then: exit $fail
#   inside it ($dir/drive.sh, with these helpers sourced): real key presses
#   and mouse input through the X server (xdotool) into a viewer window.
#
# Two kinds of input: press, click, combo, typed and drag hold keys and
# buttons for fixed moments, long enough for a frame to see them on a busy
# machine; in a session opened with open_logged, tap, slide, roll, hold_key
# and type_in are paced by the window's own frames from its --edit-log
# (after_frames), and waits poll the viewer's state (its title, its log)
# with a timeout rather than sleeping a fixed time.

press() { xdotool keydown --window "$wid" "$1"; sleep 0.3; xdotool keyup --window "$wid" "$1" 2>/dev/null; sleep 0.5; }
click() { xdotool mousemove --window "$wid" "$1" "$2"; sleep 0.2; xdotool mousedown 1; sleep 0.3; xdotool mouseup 1; sleep 0.5; }
combo() { xdotool keydown ctrl; sleep 0.2; press "$1"; xdotool keyup ctrl; sleep 0.3; }  # held: a frame sees it
typed() { xdotool type --delay 150 -- "$1"; sleep 0.5; }
drag() {  # x0 y0 x1 y1
  xdotool mousemove --window "$wid" "$1" "$2"; sleep 0.2; xdotool mousedown 1; sleep 0.2
  for k in 1 2 3 4 5 6; do
    xdotool mousemove --window "$wid" $(( $1 + ($3 - $1) * k / 6 )) $(( $2 + ($4 - $2) * k / 6 )); sleep 0.1
  done
  xdotool mouseup 1; sleep 0.5
}

# The viewer, one render thread, extra options `args` (the scene is
# three-balls unless args name one); waits for its window (sets $wid) and
# returns the viewer's pid in $pid. Its stdout and stderr go to
# $dir/NAME.out and .err.
# The X server resets when its last client leaves (the readiness probe of
# in_xvfb, or a session's viewer that quit), and a client that connects
# during the reset fails with "Failed to open display". Such a viewer is
# started again, up to three times, once the server answers: that failure
# is the harness's, never the viewer's. Any other failure is the test's.
# (The reset stays: with -noreset, the sessions after the first failed
# here, presumably on keys and buttons an earlier session left held.)
open_viewer() {  # name args
  local scene="--scene three-balls" k attempt
  case " $2 " in *" --scene "*) scene= ;; esac
  for attempt in 1 2 3; do
    (cd "$dir/cwd" && LIBGL_ALWAYS_SOFTWARE=1 exec "$bin" $scene --threads 1 $2) \
      >"$dir/$1.out" 2>"$dir/$1.err" &
    pid=$!
    wid=
    for k in $(seq 300); do  # a minute, unless the viewer gave up at once
      # This viewer's own window (GLFW sets _NET_WM_PID): never one of an
      # earlier session that the server has not taken down yet.
      wid=$(xdotool search --onlyvisible --pid "$pid" --name '^Whisker' 2>/dev/null | head -1)
      [ -n "$wid" ] || ! kill -0 "$pid" 2>/dev/null && break
      sleep 0.2
    done
    [ -n "$wid" ] && return 0
    kill "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    grep -q "Failed to open display" "$dir/$1.err" 2>/dev/null || break
    cat "$dir/$1.err" >>"$dir/retries.err"
    x_answers "${DISPLAY#:}" 100 || break
  done
  echo "no viewer window" >>"$dir/$1.err"
  return 1
}

# As open_viewer, with its event log in $dir/NAME.log ($log) and the
# window's place on the screen in $win_x, $win_y; waits for the first frame
# that shows a full pass of the settings it opened with.
open_logged() {  # name args
  log=$dir/$1.log
  open_viewer "$1" "$2 --edit-log $log" || return
  local X Y WIDTH HEIGHT SCREEN
  eval "$(xdotool getwindowgeometry --shell "$wid")"
  win_x=$X win_y=$Y
  log_wait "f['own_gen'] == f['gen'] and f['own_spp'] >= 1 and f['shown_gen'] == f['gen']"
}

# Polls the event log until a Python condition on it holds (names in
# tests/viewer_check.py), at most SECONDS (default 60); 1 on timeout or when
# the viewer is gone.
log_wait() {  # condition [seconds]
  VIEWER_PID=$pid "$py" "$tests/viewer_check.py" wait "$log" "$1" "${2:-60}" 2>>"$dir/waits.err"
}
# Whether the condition holds now (no waiting, nothing reported).
log_has() { VIEWER_PID=$pid "$py" "$tests/viewer_check.py" wait "$log" "$1" 0 2>/dev/null; }
# Before an action that makes an edit: mark, act, then wait_image waits for
# the first frame that shows the new settings (a quick pass, or a full one).
mark() { marked=$(grep -c '^edit ' "$log"); messages=$(grep -c '^message ' "$log"); }
wait_image() { log_wait "len(edits) > $marked and f['shown_gen'] == f['gen']" "${1:-60}"; }
# After an action that sets the panel's message: waits for the new message.
wait_message() { log_wait "len(messages) > $messages" "${1:-30}"; }
# Input for logged sessions, paced by the window itself: each step waits
# until the window has drawn three frames after it (it draws three after
# any input), so a frame has seen a key or button held, however busy the
# machine, and no step waits longer than it must.
after_frames() {  # command...
  local n k
  n=$(grep -c '^frame ' "$log")
  "$@"
  for k in $(seq 1000); do  # 30 s, unless the viewer is gone
    [ "$(grep -c '^frame ' "$log")" -ge $(( n + 3 )) ] && return 0
    running || break
    sleep 0.03
  done
  echo "timed out after 30 s waiting for 3 frames after: $*" >>"$dir/waits.err"
  return 1
}
move_to() {  # x y (window units); nothing to wait for if the pointer is there
  local X Y WINDOW SCREEN
  eval "$(xdotool getmouselocation --shell)"
  [ "$X" = "$(( $1 + win_x ))" ] && [ "$Y" = "$(( $2 + win_y ))" ] && return
  after_frames xdotool mousemove --window "$wid" "$1" "$2"
}
tap() { move_to "$1" "$2"; after_frames xdotool mousedown 1; after_frames xdotool mouseup 1; }
hold_key() {  # key [modifier]: down in one frame, up in a later one
  [ -n "${2:-}" ] && xdotool keydown --window "$wid" "$2"
  after_frames xdotool keydown --window "$wid" "$1"
  after_frames xdotool keyup --window "$wid" "$1"
  [ -n "${2:-}" ] && xdotool keyup --window "$wid" "$2"
  return 0
}
type_in() { after_frames xdotool type --delay 40 -- "$1"; }
slide() {  # x0 y0 x1 y1: a left drag in three steps
  local k
  move_to "$1" "$2"; after_frames xdotool mousedown 1
  for k in 1 2 3; do
    after_frames xdotool mousemove --window "$wid" $(( $1 + ($3 - $1) * k / 3 )) $(( $2 + ($4 - $2) * k / 3 ))
  done
  after_frames xdotool mouseup 1
}
roll() {  # x y notches: the wheel over (x, y), > 0 in (towards the look-at point), < 0 out
  local button=4 n=$3
  [ "$n" -lt 0 ] && button=5 n=$(( -n ))
  move_to "$1" "$2"
  after_frames xdotool click --repeat "$n" --delay 60 "$button"
}
# An X screenshot of the window into $dir/NAME.xwd.
shot() { xwd -id "$wid" -silent >"$dir/$1.xwd"; }
# The viewer's process is running (not gone, not a zombie waiting for wait).
running() { [ -e "/proc/$pid" ] && ! grep -q '^[0-9]* ([^)]*) Z' "/proc/$pid/stat" 2>/dev/null; }
# The window is there, its process running and its title readable.
alive() { running && xdotool getwindowname "$wid" >/dev/null 2>&1; }

# Waits until the window's title says a pass is in (at most a minute).
wait_first_pass() {
  local k
  for k in $(seq 600); do xdotool getwindowname "$wid" | grep -q " [1-9][0-9]* spp$" && return; sleep 0.1; done
}
# Waits until the window's title ends in "N spp" (at most a minute).
wait_spp() { for k in $(seq 120); do xdotool getwindowname "$wid" | grep -q " $1 spp$" && return; sleep 0.5; done; }

# Esc, then waits for the viewer to quit; its exit code goes into NAME.err.
# After edits the viewer asks first ("Quit and discard the edits?"): Enter
# says yes. NAME.asked records whether it asked.
quit_viewer() {  # name
  press Escape
  local k
  for k in $(seq 20); do running || break; sleep 0.1; done
  if running; then
    echo asked >"$dir/$1.asked"
    press Return
  fi
  wait "$pid"
  echo "exit $?" >>"$dir/$1.err"
}

# One viewer session: open, run the actions, Esc, and record the exit code.
session() {  # name args actions...
  local name=$1 args=$2
  shift 2
  open_viewer "$name" "$args" || return
  wait_first_pass
  sleep 0.5
  "$@"
  quit_viewer "$name"
}

# The outer script's start (outside the X server): $bin made absolute from
# BINARY, $tests this folder, exit 77 (ctest: skipped) when a tool is
# missing, a scratch folder $dir with cwd/ in it, removed on exit.
viewer_test_setup() {  # BINARY tools...
  bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
  tests=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  shift
  for tool in "$@"; do
    command -v "$tool" >/dev/null 2>&1 || { echo "SKIP: $tool not installed"; exit 77; }
  done
  dir=$(mktemp -d)
  trap 'rm -rf "$dir"' EXIT
  mkdir "$dir/cwd"
  fail=0
  # The interpreter itself: a version manager's python3 shim can take a
  # second to start, and the waits start one every poll.
  py=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null)
  [ -x "$py" ] || py=python3
}

# Whether a client can connect to display :$1, asked every 0.1 s for up to
# $2 tries (default 50) while process $3 (if given) lives.
x_answers() {
  local k probe=()
  if command -v xdpyinfo >/dev/null; then probe=(xdpyinfo)
  elif command -v xdotool >/dev/null; then probe=(xdotool getdisplaygeometry)
  else return 0; fi
  for k in $(seq "${2:-50}"); do
    DISPLAY=:$1 "${probe[@]}" >/dev/null 2>&1 && return 0
    [ -n "${3:-}" ] && ! kill -0 "$3" 2>/dev/null && return 1
    sleep 0.1
  done
  return 1
}

# Runs "$dir/drive.sh" in a fresh X server (1280x800) with these helpers,
# for at most SECONDS (default 300). The display number is drawn at random
# from 1000-30999 and given to the server: a server given its number checks
# the lock file before it makes its socket, so one that finds the number
# taken exits and touches nothing. (With -displayfd the server probes the
# numbers from 0 itself, and two started at once could unlink each other's
# socket: the viewer then failed with "Failed to open display :0" minutes
# after the server had answered.)
in_xvfb() {  # [seconds]
  local xpid display= try
  for try in $(seq 8); do
    display=$((1000 + (RANDOM * 32768 + RANDOM) % 30000))
    if [ -e "/tmp/.X$display-lock" ] || [ -e "/tmp/.X11-unix/X$display" ]; then display=; continue; fi
    Xvfb ":$display" -screen 0 1280x800x24 -nolisten tcp 2>>"$dir/xvfb.err" &
    xpid=$!
    # Up to 30 s for a server to answer on a busy machine; one that exits
    # (its number was taken meanwhile) is replaced at once.
    x_answers "$display" 300 "$xpid" && break
    kill "$xpid" 2>/dev/null
    wait "$xpid" 2>/dev/null
    display=
  done
  if [ -z "$display" ]; then
    echo "Xvfb did not start:"; cat "$dir/xvfb.err"; fail=1; return 1
  fi
  DISPLAY=:$display timeout "${1:-300}" env bin="$bin" dir="$dir" tests="$tests" py="$py" \
    bash -c '. "$tests/viewer_drive.sh"; . "$dir/drive.sh"'
  kill "$xpid" 2>/dev/null
  wait "$xpid" 2>/dev/null
  [ -s "$dir/waits.err" ] && { echo "--- waits that timed out"; cat "$dir/waits.err"; }
  [ -s "$dir/retries.err" ] && { echo "--- viewers started again (open_viewer)"; cat "$dir/retries.err"; }
  return 0
}

# One named check: prints ok or FAILED, and a failure sets $fail.
check() { if eval "$2"; then echo "ok: $1"; else echo "FAILED: $1"; fail=1; fi; }

# Fields of the viewer's closing line in NAME.err: generation, spp.
generation() { sed -n 's/.*generation \([0-9]*\),.*/\1/p' "$dir/$1.err"; }
closing_spp() { sed -n 's/.*generation [0-9]*, [0-9]* passes, \([0-9]*\) spp.*/\1/p' "$dir/$1.err"; }
# The eye of the N-th camera the viewer printed (C) into NAME.out: "x y z",
# or "none".
eye() {  # name n
  "$py" "$tests/viewer_check.py" cameras "$dir/$1.out" | sed -n "${2}p" | grep . || echo none
}
