# Sourced by the viewer tests' drivers (viewer_*_test.sh), which run inside
# xvfb-run: real key presses and mouse input through the X server (xdotool)
# into a viewer window. Needs $bin (the whisker binary) and $dir (the test's
# scratch folder, with a cwd/ subfolder the viewer runs in). Presses are held
# for a moment so that a frame sees them even when the machine is busy.

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

# The viewer on the three balls, one render thread, extra options `args`;
# waits for its window (sets $wid) and returns the viewer's pid in $pid.
# Its stdout and stderr go to $dir/NAME.out and .err.
open_viewer() {  # name args
  (cd "$dir/cwd" && LIBGL_ALWAYS_SOFTWARE=1 exec "$bin" --scene three-balls --threads 1 $2) \
    >"$dir/$1.out" 2>"$dir/$1.err" &
  pid=$!
  wid=$(timeout 60 xdotool search --sync --onlyvisible --name '^Whisker' | head -1)
  [ -n "$wid" ] || { echo "no viewer window" >>"$dir/$1.err"; kill "$pid"; return 1; }
}

# Waits until the window's title ends in "N spp" (at most a minute).
wait_spp() { for k in $(seq 120); do xdotool getwindowname "$wid" | grep -q " $1 spp$" && return; sleep 0.5; done; }

# One viewer session: open, run the actions, Esc, and record the exit code.
session() {  # name args actions...
  local name=$1 args=$2
  shift 2
  open_viewer "$name" "$args" || return
  sleep 2
  "$@"
  press Escape
  wait "$pid"
  echo "exit $?" >>"$dir/$name.err"
}

# The outer script's start (outside xvfb-run): $bin made absolute from
# BINARY, exit 77 (ctest: skipped) when a tool is missing, a scratch folder
# $dir with cwd/ in it, removed on exit.
viewer_test_setup() {  # BINARY tools...
  bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
  shift
  for tool in "$@"; do
    command -v "$tool" >/dev/null 2>&1 || { echo "SKIP: $tool not installed"; exit 77; }
  done
  dir=$(mktemp -d)
  trap 'rm -rf "$dir"' EXIT
  mkdir "$dir/cwd"
}
