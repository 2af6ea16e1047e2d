#!/usr/bin/env bash
# Fault tests of opening a file (whisker FILE.obj, --mesh) and of the
# viewer's scripted screenshot: odd but valid meshes render, bad ones are
# one line naming the file with exit 2, never an abort; a screenshot with no
# room for the render is refused.
#   open_faults.sh WHISKER_BINARY CASE
# Exit 0 = pass, 1 = fail (with the reason), 77 = skipped (with the reason).
set -uo pipefail
bin=$1 case=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/whisker-open-faults.XXXXXX")
xpid=
cleanup() {
  [ -n "$xpid" ] && { kill "$xpid" 2>/dev/null; wait "$xpid" 2>/dev/null; }
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work" || exit 1

fail() { echo "FAIL [$case]: $*" >&2; exit 1; }
skip() { echo "SKIP [$case]: $*" >&2; exit 77; }

# run ARGS...: the binary with its exit code in $rc, stderr in err.txt.
run() {
  "$bin" "$@" >out.txt 2>err.txt
  rc=$?
}
one_line() { [ "$(wc -l <err.txt)" -eq 1 ] || fail "$1: not one line: $(head -c 600 err.txt)"; }

# An X server of the given screen size on a free display number, drawn at
# random (as tests/viewer_drive.sh does: parallel tests never share one);
# sets DISPLAY.
start_x() {  # WxH
  command -v Xvfb >/dev/null || skip "no Xvfb"
  command -v xdotool >/dev/null || skip "no xdotool to see the X server answer"
  local try k d
  for try in $(seq 8); do
    d=$((1000 + (RANDOM * 32768 + RANDOM) % 30000))
    [ -e "/tmp/.X$d-lock" ] || [ -e "/tmp/.X11-unix/X$d" ] && continue
    Xvfb ":$d" -screen 0 "${1}x24" -nolisten tcp 2>>xvfb.err &
    xpid=$!
    for k in $(seq 300); do
      DISPLAY=:$d xdotool getdisplaygeometry >/dev/null 2>&1 && { export DISPLAY=:$d; return 0; }
      kill -0 "$xpid" 2>/dev/null || break
      sleep 0.1
    done
    kill "$xpid" 2>/dev/null
    wait "$xpid" 2>/dev/null
    xpid=
  done
  fail "Xvfb did not start: $(head -c 600 xvfb.err)"
}

tri='v 0 0 0\nv 1 0 0\nv 0 1 0\n'
case $case in
  obj-file-never-aborts)
    # Valid meshes with a vertex no face uses far off, a mesh far smaller
    # or larger than the room, one zero-area face beside a real one: each
    # renders as FILE (headless, and the viewer's path, which without a
    # display stops at the window: exit 3). Meshes with nothing to show:
    # exit 2, one line naming the file.
    printf "${tri}v 1e30 1e30 1e30\nf 1 2 3\n" >far.obj
    printf "${tri}v -3e38 0 0\nf 1 2 3\n" >farthest.obj
    printf 'v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n' >tiny.obj
    printf 'v 0 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n' >huge.obj
    printf "${tri}v 1e20 0 0\nf 1 2 3\nf 4 4 1\n" >stray-face.obj
    for obj in far.obj farthest.obj tiny.obj huge.obj stray-face.obj; do
      run --headless "$obj" --quiet --frames 1 --indirect off --connect off --stats s.json
      [ "$rc" -eq 0 ] || fail "$obj: exit $rc: $(head -c 600 err.txt)"
      run "$obj"
      [ "$rc" -eq 3 ] || [ -n "${DISPLAY:-}" ] || fail "$obj, viewer: exit $rc: $(head -c 600 err.txt)"
    done
    printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n' >line.obj
    printf "${tri}" >points.obj
    : >empty.obj
    mkdir folder.obj
    mkfifo fifo.obj
    for obj in line.obj points.obj empty.obj folder.obj fifo.obj; do
      for args in "--headless $obj --quiet --frames 1 --stats s.json" "$obj"; do
        # shellcheck disable=SC2086
        DISPLAY= timeout 20 "$bin" $args >out.txt 2>err.txt
        rc=$?
        [ "$rc" -ne 134 ] || fail "$args aborted (exit 134): $(head -c 300 err.txt)"
        [ "$rc" -eq 2 ] || fail "$args: exit $rc, expected 2: $(head -c 600 err.txt)"
        grep -q "^whisker: $obj: " err.txt || fail "$args: does not name $obj first: $(head -c 600 err.txt)"
        grep -q -- "--mesh" err.txt && fail "$args: names --mesh, which was not given: $(cat err.txt)"
        one_line "$args"
      done
    done
    ;;
  screenshot-without-room)
    # A screen so small (16 x 16) that the panel cannot stand beside the
    # image: the panel steps aside (Tab brings it back), the image takes the
    # window, scaled down, and the screenshot holds it. No crash, no message.
    cat >scene.json <<'JSON'
{"name": "faults", "camera": {"position": [0, 0, 55], "look_at": [0, 0, 0], "width": 32, "height": 32},
 "light": {"position": [-10, 20, 40]},
 "spheres": [{"center": [0, 0, 0], "radius": 10, "material": {"type": "diffuse", "albedo": [1, 1, 1]}}]}
JSON
    start_x 16x16
    LIBGL_ALWAYS_SOFTWARE=1 timeout 60 "$bin" --scene scene.json --threads 1 --frames 1 \
      --screenshot shot.png >out.txt 2>err.txt
    rc=$?
    grep -q "cannot open" err.txt && skip "no OpenGL window here: $(head -c 300 err.txt)"
    grep -q "built without the viewer" err.txt && skip "this build has no viewer"
    [ "$rc" -eq 0 ] || fail "exit $rc, expected 0: $(head -c 600 err.txt)"
    [ -s shot.png ] && [ -s shot.png.json ] || fail "no screenshot written"
    [ "$(tr -d ' \n' <shot.png.json | grep -o '"render_rect":\[[0-9,]*\]')" = '"render_rect":[0,0,16,16]' ] ||
      fail "the image does not fill the window: $(head -c 600 shot.png.json)"
    ! grep -q '^whisker:' err.txt || fail "a message: $(head -c 600 err.txt)"
    ;;
  *)
    fail "unknown case $case"
    ;;
esac
exit 0
