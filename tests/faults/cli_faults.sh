#!/usr/bin/env bash
# Fault tests of the headless command line: signals during the render and
# during the write, a full disk, a read-only folder, special files as output
# targets, and bad input that must be refused with exit 2.
#   cli_faults.sh WHISKER_BINARY CASE
# Exit 0 = pass, 1 = fail (with the reason), 77 = skipped (with the reason).
set -uo pipefail
bin=$1 case=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/whisker-faults.XXXXXX")
mounted=()
cleanup() {
  local m
  for m in "${mounted[@]}"; do umount "$m" 2>/dev/null; done
  chmod -R u+w "$work" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work" || exit 1

fail() { echo "FAIL [$case]: $*" >&2; exit 1; }
skip() { echo "SKIP [$case]: $*" >&2; exit 77; }
note() { echo "[$case] $*" >&2; }

# A quick scene of the given size: the floor wall and one ball.
scene() {
  cat >"scene.json" <<JSON
{"name": "faults", "camera": {"position": [0, 0, 55], "look_at": [0, 0, 0], "width": $1, "height": $2},
 "light": {"position": [-10, 20, 40]},
 "spheres": [{"center": [0, -1000, 0], "radius": 990, "material": {"type": "diffuse", "albedo": [0, 0, 1]}},
             {"center": [0, 0, 0], "radius": 10, "material": {"type": "diffuse", "albedo": [1, 1, 1]}}]}
JSON
}

# run ARGS...: the binary with its exit code in $rc, stderr in err.txt.
run() {
  "$bin" "$@" >out.txt 2>err.txt
  rc=$?
}
expect_rc() { [ "$rc" -eq "$1" ] || fail "exit $rc, expected $1; stderr: $(head -c 600 err.txt)"; }
expect_err() { grep -qiE -- "$1" err.txt || fail "stderr does not match /$1/: $(head -c 600 err.txt)"; }
no_temp_files() {
  local left
  left=$(find "${1:-.}" -name '.*.tmp-*' 2>/dev/null)
  [ -z "$left" ] || fail "temporary files left behind: $left"
}
# A PFM at its final name is whole: header plus width x height x 12 bytes.
pfm_whole() {
  local f=$1 w=$2 h=$3 size header
  header=$(printf 'PF\n%d %d\n-1.0\n' "$w" "$h" | wc -c)
  size=$(stat -c %s "$f")
  [ "$size" -eq $((header + w * h * 12)) ] || fail "$f is $size bytes, a whole one is $((header + w * h * 12))"
}
need_root_mount() {
  [ "$(id -u)" -eq 0 ] || skip "needs root to mount a small tmpfs (run the tests as root to cover it)"
  mkdir -p "$1"
  mount -t tmpfs -o "size=${2:-64k}${3:+,$3}" whisker-faults "$1" 2>/dev/null ||
    skip "cannot mount a tmpfs here (container without CAP_SYS_ADMIN?)"
  mounted+=("$PWD/$1")
}
# under_memory_cap MB CMD...: runs CMD with at most MB megabytes, so that a
# failure cannot exhaust the machine: ulimit -v, or under a sanitizer (which
# reserves terabytes of address space for its shadow memory and cannot start
# under ulimit -v) its own limit. (No `ldd | grep -q` here: under pipefail
# grep's early exit fails ldd with SIGPIPE, and the test read "no sanitizer".)
under_memory_cap() {
  local mb=$1
  shift
  if [ -n "${TSAN_OPTIONS:-}${ASAN_OPTIONS:-}" ] || [ "$(ldd "$bin" 2>/dev/null | grep -c 'lib[at]san')" -gt 0 ]; then
    ASAN_OPTIONS="${ASAN_OPTIONS:-}${ASAN_OPTIONS:+:}hard_rss_limit_mb=$mb" \
      TSAN_OPTIONS="${TSAN_OPTIONS:-}${TSAN_OPTIONS:+:}memory_limit_mb=$mb" "$@"
  else
    (ulimit -v $((mb * 1000)) && "$@")
  fi
}
sanitized() {
  [ -n "${TSAN_OPTIONS:-}${ASAN_OPTIONS:-}" ] || [ "$(ldd "$bin" 2>/dev/null | grep -c 'lib[at]san')" -gt 0 ]
}
have_exr() {
  scene 8 8
  "$bin" --headless --scene scene.json --quiet --out-float probe.exr >/dev/null 2>&1
}
# Starts a long render in the background (SIGINT not ignored, as in a
# terminal) with all three outputs; its pid in $pid.
start_long_render() {
  scene 128 128
  env --default-signal=INT "$bin" --headless --scene scene.json --quiet --frames 1000000 --spp 1 \
    --out img.png --out-float img.pfm --stats stats.json >out.txt 2>err.txt &
  pid=$!
  sleep 1.5
  kill -0 "$pid" 2>/dev/null || fail "the render ended within 1.5 s: $(cat err.txt)"
}
# Starts a 1024 x 1024 render, one sample, and waits until the writer's
# temporary file exists; then sends the signal. Sets $target, $pid.
signal_mid_write() {
  local sig=$1 ext=pfm tmp i
  have_exr && ext=exr
  scene 1024 1024
  target=img.$ext
  for i in 1 2 3 4 5; do
    rm -f "$target" .img.*
    env --default-signal=INT "$bin" --headless --scene scene.json --quiet --frames 1 --spp 1 \
      --depth 0 --out-float "$target" >out.txt 2>err.txt &
    pid=$!
    # The write in progress: an unnamed temporary file (O_TMPFILE, shown in
    # /proc as "#INODE (deleted)") or a named ".img.EXT.tmp-RANDOM".
    writing() {
      ls -l "/proc/$pid/fd" 2>/dev/null | grep -qE -- "$work/(#[0-9]+ \(deleted\)|\.$target\.tmp-)"
    }
    tmp="the temporary file"
    while ! writing && kill -0 "$pid" 2>/dev/null; do :; done
    if writing && kill -"$sig" "$pid" 2>/dev/null; then
      wait "$pid"
      rc=$?
      note "SIG$sig sent while $tmp existed (attempt $i); exit $rc"
      return 0
    fi
    wait "$pid"
  done
  skip "could not catch the write in progress in 5 attempts"
}

# signal_mid_render SIG CODE: SIG in a long headless render; the passes
# completed are written to every output, the stats say how many, exit CODE.
signal_mid_render() {
  start_long_render
  kill -"$1" "$pid"
  wait "$pid"
  rc=$?
  expect_rc "$2"
  expect_err "interrupt"
  for f in img.png img.pfm stats.json; do [ -f "$f" ] || fail "$f not written after SIG$1"; done
  pfm_whole img.pfm 128 128
  passes=$(python3 -c 'import json,sys; print(json.load(open("stats.json"))["passes"])') ||
    fail "stats.json is not JSON"
  [ "$passes" -ge 1 ] && [ "$passes" -lt 1000000 ] || fail "stats say $passes passes"
  no_temp_files
}

case $case in
  sigint-render-writes-passes-so-far)
    # Ctrl-C in a long headless render: the passes completed are written to
    # every output, the stats say how many, the exit code is 130.
    signal_mid_render INT 130
    ;;
  sigkill-render-leaves-nothing)
    # A kill -9 mid-render: nothing at the final names, nothing half-written.
    start_long_render
    kill -KILL "$pid"
    wait "$pid"
    rc=$?
    expect_rc 137
    for f in img.png img.pfm stats.json; do [ ! -e "$f" ] || fail "$f exists after kill -9 mid-render"; done
    no_temp_files
    ;;
  sigint-mid-write-cleans-up)
    # Ctrl-C while the output is being written: the final name holds nothing
    # or the whole file, no temporary file stays behind, exit 130.
    signal_mid_write INT
    expect_rc 130
    [ ! -e "$target" ] || [ "${target##*.}" != pfm ] || pfm_whole "$target" 1024 1024
    no_temp_files
    ;;
  sigkill-mid-write-never-partial)
    # kill -9 while writing: the final name never holds a partial file (the
    # temporary file may stay: no process can clean up after SIGKILL).
    signal_mid_write KILL
    expect_rc 137
    [ ! -e "$target" ] || fail "$target appeared although the write was killed"
    ;;
  disk-full-png | disk-full-pfm | disk-full-exr | disk-full-stats)
    # Each output kind on a full disk: exit 2 with the reason, nothing at the
    # final name, no temporary file left.
    kind=${case#disk-full-}
    [ "$kind" != exr ] || have_exr || skip "this build has no OpenEXR"
    need_root_mount full 64k
    scene 256 256
    dd if=/dev/zero of=full/filler bs=1k count=64 2>/dev/null  # fills it (dd stops at ENOSPC)
    case $kind in
      png) opt=(--out full/img.png) ;; pfm) opt=(--out-float full/img.pfm) ;;
      exr) opt=(--out-float full/img.exr) ;; stats) opt=(--stats full/stats.json) ;;
    esac
    run --headless --scene scene.json --quiet --frames 1 --spp 4 "${opt[@]}"
    expect_rc 2
    expect_err "${opt[1]}.*(no space|cannot write)"
    [ ! -e "${opt[1]}" ] || fail "${opt[1]} exists ($(stat -c %s "${opt[1]}") bytes) after a failed write"
    no_temp_files full
    ;;
  readonly-folder)
    # Outputs into a folder that cannot be written: refused before rendering.
    if [ "$(id -u)" -eq 0 ]; then
      need_root_mount ro 64k ro  # root ignores permission bits; a read-only mount does not
    else
      mkdir ro && chmod 555 ro
    fi
    scene 32 32
    for opt in "--out ro/img.png" "--out-float ro/img.pfm" "--stats ro/stats.json"; do
      # shellcheck disable=SC2086
      run --headless --scene scene.json --quiet --frames 1 $opt
      expect_rc 2
      expect_err "^whisker: ${opt%% *} ro/.*not writable"
      [ -z "$(ls -A ro)" ] || fail "$opt created $(ls -A ro)"
    done
    ;;
  special-fifo-targets)
    # A FIFO at an output's name must not be replaced by a regular file.
    scene 32 32
    for opt in "--stats stats.json" "--out img.png" "--out-float img.pfm"; do
      f=${opt#* }
      rm -f "$f" && mkfifo "$f"
      # shellcheck disable=SC2086
      timeout 20 "$bin" --headless --scene scene.json --quiet --frames 1 $opt >out.txt 2>err.txt
      rc=$?
      expect_rc 2
      expect_err "^whisker: ${opt%% *} $f"
      [ -p "$f" ] || fail "$opt replaced the FIFO $f with $(stat -c %F "$f")"
    done
    no_temp_files
    ;;
  special-device-target)
    # A device node (a private copy of /dev/null's, never the real one) as
    # --stats must not be replaced.
    [ "$(id -u)" -eq 0 ] || skip "mknod needs root"
    mknod null c 1 3 || skip "mknod refused here"
    scene 32 32
    run --headless --scene scene.json --quiet --frames 1 --stats null
    expect_rc 2
    expect_err "^whisker: --stats null"
    [ -c null ] || fail "--stats replaced the device node with $(stat -c %F null)"
    ;;
  float-options-refuse-nan)
    # Every float option refuses NaN and infinities, naming the option; seeds
    # are capped as in scene files.
    scene 32 32
    for bad in "--intensity nan" "--intensity inf" "--intensity -nan" "--seed -1" \
               "--seed 99999999999999999999"; do
      # shellcheck disable=SC2086
      run --headless --scene scene.json --quiet --frames 1 --stats s.json $bad
      expect_rc 2
      expect_err "^whisker: .*${bad%% *}"
      [ ! -e s.json ] || fail "$bad rendered"
    done
    ;;
  mesh-filesystem-errors)
    # File-system errors while loading an OBJ (a material library name over
    # 255 bytes, a symlink loop) are the usual one-line message and exit 2.
    scene 32 32
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >base.obj
    { printf 'mtllib %0300d.mtl\n' 0; cat base.obj; } >long.obj
    ln -s loop loop
    { echo 'mtllib loop/x.mtl'; cat base.obj; } >loop.obj
    for obj in long.obj loop.obj; do
      run --headless --scene cat --mesh "$PWD/$obj" --quiet --frames 1 --spp 1 --stats s.json
      [ "$rc" -ne 134 ] || fail "$obj aborted the program (exit 134): $(head -c 300 err.txt)"
      expect_rc 2
      expect_err "^whisker: .*$obj"
      [ "$(wc -l <err.txt)" -eq 1 ] || fail "$obj: more than one line: $(head -c 600 err.txt)"
    done
    ;;
  sigterm-render-writes-passes-so-far)
    # SIGTERM (a batch system's stop) in a long headless render: like
    # Ctrl-C, the passes completed are written; the exit code is 128 + 15.
    signal_mid_render TERM 143
    ;;
  disk-full-sum | disk-full-checkpoint | disk-full-merge)
    # The accumulation file (--out-sum, at the end or as a checkpoint) and
    # the outputs of `whisker merge` on a full disk: exit 2 naming the file,
    # nothing at the final name, no temporary file left.
    have_exr || skip "this build has no OpenEXR"
    scene 64 64
    "$bin" --headless --scene scene.json --quiet --threads 1 --spp 1 --samples 0:1 --out-sum p1.exr >/dev/null 2>&1 &&
      "$bin" --headless --scene scene.json --quiet --threads 1 --spp 1 --samples 1:2 --out-sum p2.exr >/dev/null 2>&1 ||
      fail "could not render the parts"
    need_root_mount full 64k
    dd if=/dev/zero of=full/filler bs=1k count=64 2>/dev/null
    case ${case#disk-full-} in
      sum) run --headless --scene scene.json --quiet --threads 1 --frames 2 --out-sum full/sum.exr; t=full/sum.exr ;;
      checkpoint) run --headless --scene scene.json --quiet --threads 1 --frames 3 --out-sum full/sum.exr --checkpoint 0; t=full/sum.exr ;;
      merge)
        for o in "--out full/m.exr" "--out full/m.pfm" "--out full/m.png" "--stats full/m.json"; do
          # shellcheck disable=SC2086
          run merge p1.exr p2.exr $o
          expect_rc 2
          expect_err "^whisker: ${o#* }.*no space"
          [ ! -e "${o#* }" ] || fail "merge $o: ${o#* } exists after a failed write"
        done
        t=full/m.json ;;
    esac
    expect_rc 2
    expect_err "$t.*no space"
    [ ! -e "$t" ] || fail "$t exists ($(stat -c %s "$t") bytes) after a failed write"
    no_temp_files full
    ;;
  special-targets-every-option)
    # No output option replaces a FIFO, a device node or what a symbolic link
    # to one names: --out-sum and --screenshot too (checked before any
    # window opens), and the outputs of `whisker merge`.
    [ "$(id -u)" -eq 0 ] && mknod null c 1 3 2>/dev/null || mkfifo null
    mkfifo fifo.exr
    ln -s null link-to-null.png
    scene 32 32
    for t in fifo.exr null link-to-null.png; do
      for opt in --out-sum --screenshot --out --stats; do
        headless=(--headless --quiet)
        [ "$opt" != --screenshot ] || headless=()  # the viewer's option, checked before a window opens
        timeout 20 "$bin" "${headless[@]}" --scene scene.json --frames 1 "$opt" "$t" >out.txt 2>err.txt
        rc=$?
        expect_rc 2
        expect_err "^whisker: $opt $t"
      done
    done
    if have_exr; then
      scene 32 32
      "$bin" --headless --scene scene.json --quiet --spp 1 --samples 0:1 --out-sum p1.exr >/dev/null 2>&1 ||
        fail "could not render a part"
      for o in "--out fifo.exr" "--stats null" "--stats link-to-null.png" "--out link-to-null.png"; do
        # shellcheck disable=SC2086
        timeout 20 "$bin" merge p1.exr $o >out.txt 2>err.txt
        rc=$?
        expect_rc 2
        expect_err "^whisker: .*${o#* }"
      done
    fi
    [ -p fifo.exr ] || fail "fifo.exr was replaced by $(stat -c %F fifo.exr)"
    [ -c null ] || [ -p null ] || fail "null was replaced by $(stat -c %F null)"
    [ -L link-to-null.png ] || fail "the symbolic link was replaced"
    no_temp_files
    ;;
  long-output-names)
    # An output whose name is legal but near NAME_MAX (250 of 255 bytes):
    # the temporary file beside it must have a legal name too.
    scene 32 32
    long=$(printf 'n%.0s' $(seq 1 246))
    run --headless --scene scene.json --quiet --frames 1 --out "$long.png" --out-float "$long.pfm" \
      --stats "$long.json"
    expect_rc 0
    for f in "$long.png" "$long.pfm" "$long.json"; do [ -s "$f" ] || fail "${f:0:20}... was not written"; done
    pfm_whole "$long.pfm" 32 32
    no_temp_files
    ;;
  outputs-never-clobber-inputs)
    # An output may not name an input (the scene,
    # the mesh, --resume, a part of a merge) nor another output of the same
    # run; the one exception is --out-sum X --resume X (continue in place).
    have_exr || skip "this build has no OpenEXR"
    scene 32 32
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
    "$bin" --headless --scene scene.json --quiet --spp 1 --samples 0:1 --out-sum p1.exr >/dev/null 2>&1 &&
      "$bin" --headless --scene scene.json --quiet --spp 1 --samples 1:2 --out-sum p2.exr >/dev/null 2>&1 ||
      fail "could not render the parts"
    sums=$(md5sum scene.json tri.obj p1.exr p2.exr)
    for args in "--stats scene.json" "--stats ./scene.json" "--out-float p1.exr --resume p1.exr" \
                "--stats p1.exr --resume p1.exr" "--out x.png --stats x.png" \
                "--out-float x.exr --out-sum x.exr" "--mesh tri.obj --stats tri.obj"; do
      # shellcheck disable=SC2086
      run --headless --scene scene.json --quiet --threads 1 --frames 1 $args
      expect_rc 2
      [ "$sums" = "$(md5sum scene.json tri.obj p1.exr p2.exr)" ] || fail "$args changed an input"
    done
    for args in "--stats p1.exr" "--out m.exr --stats m.exr" "--out m.png --out ./m.png"; do
      # shellcheck disable=SC2086
      run merge p1.exr p2.exr $args
      expect_rc 2
      [ "$sums" = "$(md5sum scene.json tri.obj p1.exr p2.exr)" ] || fail "merge $args changed a part"
    done
    run --headless --scene scene.json --quiet --threads 1 --spp 1 --frames 1 --resume p1.exr --out-sum p1.exr
    expect_rc 0
    ;;
  signal-while-loading)
    # Ctrl-C or SIGTERM before the render starts
    # (a scene read from a pipe nobody writes, a long mesh load) ends the
    # program at once; nothing is written.
    mkfifo pipe.json
    env --default-signal=INT "$bin" --headless --scene pipe.json --quiet --frames 1 --stats s.json \
      >out.txt 2>err.txt &
    pid=$!
    sleep 1
    kill -TERM "$pid"
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
      kill -KILL "$pid"
      wait "$pid"
      fail "SIGTERM while the scene was being read did not end the program within 5 s"
    fi
    wait "$pid"
    rc=$?
    expect_rc 143
    [ ! -e s.json ] || fail "s.json written although nothing was rendered"
    no_temp_files
    ;;
  scene-device-files)
    # A device as the scene file (/dev/zero, a symbolic link to it) is
    # refused at once, never read into memory (run under a memory cap).
    ln -s /dev/zero zero.json
    for sc in /dev/zero zero.json; do
      under_memory_cap 2000 timeout -s KILL 10 "$bin" --headless --scene "$sc" --quiet --frames 1 \
        --stats s.json >out.txt 2>err.txt
      rc=$?
      expect_rc 2
      expect_err "^whisker: .*$sc"
      [ "$(wc -l <err.txt)" -eq 1 ] || fail "$sc: more than one line: $(head -c 600 err.txt)"
    done
    ;;
  huge-polygon)
    # A 1.3 MB OBJ whose one face has 200,000
    # corners is loaded or refused within seconds (tinyobjloader's ear
    # clipping is quadratic: minutes; ten million corners: days).
    scene 32 32
    python3 -c "
import math
n = 200000
with open('poly.obj', 'w') as f:
    for i in range(n):
        f.write('v %.6f %.6f 0\n' % (math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n)))
    f.write('f ' + ' '.join(str(i + 1) for i in range(n)) + '\n')
" || skip "python3 missing"
    timeout -s KILL 20 "$bin" --headless --scene cat --mesh "$PWD/poly.obj" --quiet --frames 1 --spp 1 \
      --stats s.json >out.txt 2>err.txt
    rc=$?
    [ "$rc" -ne 137 ] || fail "a face of 200,000 corners took over 20 s to load"
    [ "$rc" -eq 0 ] || { expect_rc 2; expect_err "^whisker: .*poly.obj"; }
    ;;
  messages-one-line)
    # Refusals are one line even when the input
    # holds line breaks (an unknown key "a\nb" in JSON) or the parser's own
    # message ends in one (tinyobjloader's, for "f 1/x 2 3").
    scene 32 32
    printf '{"na\\nme\\u001b[2J": 1}' >key.json
    { printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n'; printf 'f 1/x 2 3\n'; } >junk.obj
    run --headless --scene key.json --quiet --frames 1 --stats s.json
    expect_rc 2
    [ "$(wc -l <err.txt)" -eq 1 ] || fail "unknown key with a line break: $(wc -l <err.txt) lines: $(head -c 300 err.txt)"
    ! grep -q $'\x1b' err.txt || fail "the message echoes a raw escape character"
    run --headless --scene cat --mesh "$PWD/junk.obj" --quiet --frames 1 --spp 1 --stats s.json
    expect_rc 2
    expect_err "^whisker: .*junk.obj"
    [ "$(wc -l <err.txt)" -eq 1 ] || fail "bad face token: $(wc -l <err.txt) lines: $(head -c 300 err.txt)"
    ;;
  empty-option-values)
    # An option given an empty value is refused
    # naming it, not taken as absent (--out "" beside --stats silently wrote
    # no image; --samples "" rendered the default range).
    scene 32 32
    for opt in --samples --light --mesh --resume --out --out-float --out-sum; do
      run --headless --scene scene.json --quiet --frames 1 --stats s.json "$opt" ""
      expect_rc 2
      expect_err "^whisker: $opt"
      rm -f s.json
    done
    ;;
  sighup-render-writes-passes-so-far)
    # SIGHUP (the terminal or the ssh session closed) in a long headless
    # render: like SIGTERM, the passes completed are written; exit 128 + 1.
    signal_mid_render HUP 129
    ;;
  sigpipe-reader-gone)
    # The reader of the progress or of the summary line went away (a pipe
    # into `head -c1`): the render goes on and writes its outputs, exit 0.
    scene 64 64
    "$bin" --headless --scene scene.json --frames 300 --spp 1 --progress 0.02 --out img.png \
      --stats stats.json 2>&1 | head -c1 >/dev/null
    rc=${PIPESTATUS[0]}
    expect_rc 0
    for f in img.png stats.json; do [ -s "$f" ] || fail "$f not written when the progress reader left"; done
    rm -f img.png
    "$bin" --headless --scene scene.json --quiet --frames 1 --out img.png | true
    rc=${PIPESTATUS[0]}
    expect_rc 0
    [ -s img.png ] || fail "img.png not written when the summary's reader left"
    no_temp_files
    ;;
  outputs-never-clobber-scene-meshes)
    # A mesh the scene file names (not given with --mesh) is an input too:
    # --stats tri.obj replaced it with JSON, exit 0.
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
    echo '{"camera": {"width": 16, "height": 16}, "meshes": [{"path": "tri.obj"}]}' >mesh.json
    sum=$(md5sum tri.obj)
    for out in tri.obj ./tri.obj "$PWD/tri.obj"; do
      run --headless --scene mesh.json --quiet --frames 1 --stats "$out"
      expect_rc 2
      expect_err "^whisker: --stats $out: is the mesh input"
      [ "$sum" = "$(md5sum tri.obj)" ] || fail "--stats $out changed the scene's mesh"
    done
    ;;
  mesh-option-needs-meshes)
    # --mesh on a scene without meshes was ignored silently (even a file that
    # cannot be read): refused, naming the option and the scene.
    scene 16 16
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
    run --headless --scene scene.json --quiet --frames 1 --stats s.json --mesh tri.obj
    expect_rc 2
    expect_err "^whisker: --mesh tri.obj: .*scene.json.*no meshes"
    [ ! -e s.json ] || fail "rendered although --mesh had nothing to replace"
    ;;
  output-extensions)
    # Extensions are read in any case for every output (x.EXR was refused by
    # --out-sum and M.PNG by merge, while --out-float took x.EXR), and a
    # --screenshot not ending in .png is refused (a PNG was written as .txt).
    have_exr || skip "this build has no OpenEXR"
    scene 16 16
    run --headless --scene scene.json --quiet --spp 1 --samples 0:1 --out-sum P1.EXR
    expect_rc 0
    run merge P1.EXR --out M.PNG --out M.EXR --out M.Pfm
    expect_rc 0
    for f in M.PNG M.EXR M.Pfm; do [ -s "$f" ] || fail "merge did not write $f"; done
    pfm_whole M.Pfm 16 16
    run --scene scene.json --frames 1 --screenshot shot.txt
    expect_rc 2
    expect_err "^whisker: --screenshot shot.txt: must end in .png"
    [ ! -e shot.txt ] || fail "shot.txt written"
    ;;
  scene-duplicate-keys)
    # A key given twice in one object was taken silently, the last winning
    # ("width": 16 ... "width": 4096): refused, naming the field.
    for body in '{"camera": {"width": 16, "height": 16, "width": 4096}}|camera.width' \
                '{"name": "a", "name": "b"}|name' \
                '{"spheres": [{"center": [0,0,0], "radius": 1, "material": {"type": "mirror", "type": "glass"}}]}|spheres\[0\]\.material\.type' \
                '{"description": [1, {"a": 1, "a": 2}]}|description\[1\]\.a'; do
      printf '%s' "${body%|*}" >dup.json
      run --headless --scene dup.json --quiet --frames 1 --stats s.json
      expect_rc 2
      expect_err "^whisker: dup.json: ${body##*|}: given twice"
    done
    echo '{"a": {"k": 1}, "b": {"k": 2}, "description": [{"k": 1}, {"k": 2}]}' >same.json
    run --headless --scene same.json --quiet --frames 1 --stats s.json
    expect_err "unknown key"  # the same key in different objects is no duplicate
    ;;
  camera-up-degenerate)
    # An up vector whose length squared leaves float's range gave NaN rays:
    # a black image, exit 0. Any finite nonzero length is a direction now,
    # the image that of the unit up bit for bit; only an up along the view
    # is refused, naming the field.
    for pair in '1e-30,0,0 1,0,0' '0,1e-40,0 0,1,0' '1e30,1e30,0 1,1,0'; do
      for up in $pair; do
        echo "{\"camera\": {\"up\": [$up], \"width\": 16, \"height\": 16}}" >up.json
        run --headless --scene up.json --quiet --frames 1 --out-float "up-$up.pfm"
        expect_rc 0
      done
      set -- $pair
      cmp -s "up-$1.pfm" "up-$2.pfm" || fail "up [$1] did not render as up [$2]"
    done
    echo '{"camera": {"up": [0, 0, 1e-20], "width": 16, "height": 16}}' >up.json
    run --headless --scene up.json --quiet --frames 1 --stats s.json
    expect_rc 2
    expect_err "^whisker: up.json: camera.up: must not be parallel to the view direction"
    ;;
  non-utf8-names)
    # File names may hold any bytes: a scene named by its file's stem, or a
    # --mesh path, that is not UTF-8 made every render fail after loading
    # with the JSON library's message ("type_error.316"), naming nothing.
    scene 16 16
    sed 's/"name": "faults", //' scene.json >$'\xff.json'
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >$'m\xfe.obj'
    echo '{"camera": {"width": 16, "height": 16}, "meshes": [{"path": "x.obj"}]}' >mesh.json
    run --headless --scene $'./\xff.json' --quiet --frames 1 --out a.png --stats a.json
    expect_rc 0
    python3 -c 'import json,sys; json.load(open("a.json"))' 2>/dev/null || fail "a.json is not JSON"
    run --headless --scene mesh.json --mesh $'m\xfe.obj' --quiet --frames 1 --stats b.json
    expect_rc 0
    [ -s a.png ] && [ -s b.json ] || fail "outputs missing"
    ;;
  obj-bad-normals)
    # "vn" lines were not checked: a NaN normal rendered its triangles black
    # (exit 0). Refused naming the line; a zero, tiny or huge normal (whose
    # float normalising fails) stands for the triangle's own normal.
    printf 'v -20 -20 0\nv 20 -20 0\nv 0 20 0\nvn nan 0 1\nf 1//1 2//1 3//1\n' >nan.obj
    printf 'v -20 -20 0\nv 20 -20 0\nv 0 20 0\nvn 0 1\nf 1//1 2//1 3//1\n' >two.obj
    for obj in nan.obj two.obj; do
      echo "{\"camera\": {\"width\": 16, \"height\": 16}, \"meshes\": [{\"path\": \"$obj\", \"vertex_normals\": true}]}" >n.json
      run --headless --scene n.json --quiet --frames 1 --stats s.json
      expect_rc 2
      expect_err "^whisker: n.json: meshes\[0\].path: .*$obj:4: normal"
    done
    for vn in '0 0 1' '0 0 0' '0 0 1e-30' '0 0 1e25'; do
      printf 'v -20 -20 0\nv 20 -20 0\nv 0 20 0\nvn %s\nf 1//1 2//1 3//1\n' "$vn" >n.obj
      echo '{"camera": {"width": 16, "height": 16}, "light": {"position": [0, 0, 40]}, "meshes": [{"path": "n.obj", "vertex_normals": true}]}' >n.json
      run --headless --scene n.json --quiet --frames 1 --out-float "n-${vn// /_}.pfm"
      expect_rc 0
    done
    for vn in 0_0_0 0_0_1e-30 0_0_1e25; do
      cmp -s "n-$vn.pfm" n-0_0_1.pfm || fail "vn ${vn//_/ } did not shade as the face normal"
    done
    ;;
  accumulation-damaged-header)
    # A part whose header claims 40000 x 40000 pixels (35 KB on disk) had
    # its 51 GB allocated before the read failed; one whose sample range
    # lies past 2^32 was resumed, the sample counter running past 32 bits.
    have_exr || skip "this build has no OpenEXR"
    scene 64 64  # big enough that the claimed size's line offset table is there to read
    run --headless --scene scene.json --quiet --spp 1 --samples 1000000000:1000000002 --out-sum p.exr
    expect_rc 0
    python3 - <<'PY' || skip "python3 missing"
import struct
d = bytearray(open('p.exr', 'rb').read())
tag = b'dataWindow\x00box2i\x00'
k = d.find(tag) + len(tag) + 4
big = d[:k] + struct.pack('<4i', 0, 0, 39999, 39999) + d[k + 16:]
open('big.exr', 'wb').write(big)
assert d.count(b'1000000000:1000000002') == 1
open('far.exr', 'wb').write(bytes(d).replace(b'1000000000:1000000002', b'9000000000:9000000002'))
PY
    for cmd in "merge big.exr --out m.png" \
               "--headless --scene scene.json --quiet --frames 1 --resume big.exr --out-sum r.exr"; do
      # shellcheck disable=SC2086
      under_memory_cap 3000 timeout -s KILL 20 "$bin" $cmd >out.txt 2>err.txt
      rc=$?
      expect_rc 2
      expect_err "^whisker: .*big.exr: header gives 40000 x 40000 pixels"
    done
    run --headless --scene scene.json --quiet --spp 1 --frames 4 --resume far.exr --out-sum r.exr
    expect_rc 2
    # Its range edited by hand: the header checksum refuses it before the
    # range's own check (below 2^30, as --samples) is reached.
    expect_err "^whisker: --resume far.exr: damaged: its header does not match its checksum"
    [ ! -e r.exr ] || fail "far.exr was resumed"
    ;;
  checkpoint-warns-once)
    # A --checkpoint that cannot be written warned on every pass (19 lines a
    # second at --checkpoint 0 on a full disk): the same failure is told once.
    have_exr || skip "this build has no OpenEXR"
    need_root_mount full 64k
    scene 32 32
    dd if=/dev/zero of=full/filler bs=1k count=64 2>/dev/null
    run --headless --scene scene.json --quiet --threads 1 --frames 400 --out-sum full/sum.exr --checkpoint 0
    expect_rc 2
    n=$(grep -c 'warning: checkpoint' err.txt)
    [ "$n" -le 1 ] || fail "the checkpoint failure was told $n times"
    no_temp_files full
    ;;
  input-slips)
    # A split with a trailing comma or a space was taken ("4," as 4); one too
    # large said "expected integers"; an OBJ that starts with a UTF-8 byte
    # order mark was refused; a scene behind a symbolic link loop was "not
    # found"; --intensity took hex and spaces (0x10, " 5"); an option given twice read "At Most 1 required but received 2".
    # Each now says what it is.
    scene 16 16
    for bad in '4,' ' 4' '4,,4' '+4' '4, 4'; do
      run --headless --scene scene.json --quiet --split "$bad" --stats s.json
      expect_rc 2
      expect_err "^whisker: --split .*expected integers separated by commas"
    done
    for bad in '0x10' ' 5' '+5' '5 '; do
      run --headless --scene scene.json --quiet --intensity "$bad" --stats s.json
      expect_rc 2
      expect_err "^whisker: --intensity .*expected a number"
    done
    run --headless --scene scene.json --quiet --intensity 1e400 --stats s.json
    expect_rc 2
    expect_err "^whisker: --intensity 1e400: must be in \[0, 1e\+?30\]"
    run --headless --scene scene.json --quiet --frames 1 --frames 2 --stats s.json
    expect_rc 2
    expect_err "^whisker: --frames: given more than once; give it once$"
    run --headless --scene scene.json --quiet --split 99999999999 --stats s.json
    expect_rc 2
    expect_err "^whisker: --split .*factors must be in \[1, [0-9]+\], got 99999999999"
    printf 'v -20 -20 0\nv 20 -20 0\nv 0 20 0\nf 1 2 3\n' >plain.obj
    { printf '\xef\xbb\xbf'; cat plain.obj; } >bom.obj
    for obj in plain bom; do
      echo "{\"camera\": {\"width\": 16, \"height\": 16}, \"meshes\": [{\"path\": \"$obj.obj\"}]}" >m.json
      run --headless --scene m.json --quiet --frames 1 --out-float "$obj.pfm"
      expect_rc 0
    done
    cmp -s plain.pfm bom.pfm || fail "the OBJ with a byte order mark rendered otherwise"
    ln -s loop-b.json loop-a.json
    ln -s loop-a.json loop-b.json
    run --headless --scene loop-a.json --quiet --stats s.json
    expect_rc 2
    expect_err "^whisker: loop-a.json: cannot open scene file: too many levels of symbolic links"
    ;;
  thread-creation-fails)
    # Worker threads that cannot all be created (their stacks do not fit
    # ulimit -v): the render hung for ever at a barrier sized for every
    # thread, deaf to SIGTERM. It runs with those created, warning once.
    sanitized && skip "a sanitizer build cannot start under ulimit -v"
    scene 32 32
    (ulimit -v 400000 && timeout -s KILL 30 "$bin" --headless --scene scene.json --quiet \
      --threads 200 --frames 2 --out img.png >out.txt 2>err.txt)
    rc=$?
    expect_rc 0
    expect_err "^whisker: warning: created [0-9]+ of 200 render threads"
    [ "$(grep -c 'render threads' err.txt)" -eq 1 ] || fail "warned more than once: $(cat err.txt)"
    [ -f img.png ] || fail "img.png not written"
    # None at all (a process limit of one, as an unprivileged user): a clean
    # refusal naming the cause.
    if [ "$(id -u)" -eq 0 ] && command -v setpriv >/dev/null; then
      chmod 777 "$work"
      setpriv --reuid=65534 --regid=65534 --clear-groups bash -c \
        "ulimit -u 1 && exec '$bin' --headless --scene scene.json --quiet --frames 1 --out nobody.png" \
        >out.txt 2>err.txt
      rc=$?
      expect_rc 2
      expect_err "^whisker: cannot create a render thread: .*ulimit -u"
    else
      note "not root: the no-thread-at-all half is not run"
    fi
    ;;
  stop-within-a-long-pass)
    # SIGTERM and Ctrl-C in a pass of 65536 samples: the stop flag was read
    # between 32 x 32 tiles only, minutes apart. Now within a sample; the
    # pass cut short is not written as a whole one.
    scene 32 32
    for sig in TERM INT; do
      env --default-signal=INT "$bin" --headless --scene scene.json --quiet --threads 2 \
        --spp 65536 --frames 1 --out img.png --stats stats.json >out.txt 2>err.txt &
      pid=$!
      sleep 1.5
      kill -"$sig" "$pid"
      for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      if kill -0 "$pid" 2>/dev/null; then
        kill -KILL "$pid"
        fail "still running 10 s after SIG$sig"
      fi
      wait "$pid"
      rc=$?
      [ "$sig" = TERM ] && expect_rc 143 || expect_rc 130
      expect_err "interrupted before the first pass ended; nothing written"
      [ ! -e img.png ] && [ ! -e stats.json ] || fail "a pass cut short was written"
    done
    ;;
  temp-files-unpredictable)
    # A symbolic link planted at the temporary name (".o.png.tmp-PID" was
    # predictable) made every output kind overwrite its target.
    scene 64 64
    echo precious >victim
    # plant_and_run OUTPUTS -- ARGS: the render with links at its outputs' old
    # temporary names, planted as soon as its pid is known.
    plant_and_run() {
      local outs=() o
      while [ "$1" != -- ]; do outs+=("$1"); shift; done
      shift
      "$bin" "$@" >/dev/null 2>err.txt &
      pid=$!
      for o in "${outs[@]}"; do ln -s "$work/victim" ".$o.tmp-$pid"; done
      wait "$pid" || fail "$* failed: $(cat err.txt)"
      for o in "${outs[@]}"; do [ -f "$o" ] && [ ! -L "$o" ] || fail "$o not written"; done
      rm -f .*.tmp-*
    }
    plant_and_run img.png img.pfm stats.json -- --headless --scene scene.json --quiet --frames 4 \
      --out img.png --out-float img.pfm --stats stats.json
    if have_exr; then
      plant_and_run f.exr sum.exr -- --headless --scene scene.json --quiet --frames 4 \
        --out-float f.exr --out-sum sum.exr --checkpoint 0
      plant_and_run m.png m.exr m.json -- merge sum.exr --out m.png --out m.exr --stats m.json
    fi
    [ "$(cat victim)" = precious ] || fail "the victim was overwritten through a planted link"
    no_temp_files
    ;;
  closed-standard-descriptors)
    # With stderr closed, the progress lines went into the checkpoint file
    # that took descriptor 2 (open(2) returns the lowest free one); with
    # stdout closed, the viewer's X connection took descriptor 1. Closed
    # standard descriptors are opened on /dev/null before anything else.
    have_exr || skip "this build has no OpenEXR"
    scene 64 64
    for closed in 0 1 2; do
      # shellcheck disable=SC2016
      env --default-signal=INT bash -c 'exec "$@" '"$closed"'>&-' - "$bin" --headless \
        --scene scene.json --spp 1 --frames 1000000 --progress 0.01 --out-sum sum.exr \
        --checkpoint 0 --out-float img.pfm 2>/dev/null </dev/null >/dev/null &
      pid=$!
      sleep 1.5
      fd=$(readlink "/proc/$pid/fd/$closed")
      kill -INT "$pid"
      wait "$pid"
      rc=$?
      [ "$fd" = /dev/null ] || fail "descriptor $closed closed at the start is $fd, not /dev/null"
      expect_rc 130
      # Whatever was written is whole and holds no text of the progress
      # (its line names the 1000000 passes asked for; a three-letter word
      # also turns up by chance in the compressed sums: 'spp' at 48 passes).
      for f in sum.exr img.pfm; do
        [ ! -e "$f" ] || ! grep -aq '/1000000 spp' "$f" || fail "progress text went into $f"
      done
      [ ! -e img.pfm ] || pfm_whole img.pfm 64 64
      if [ -e sum.exr ]; then
        run merge sum.exr --out m.pfm
        expect_rc 0
      fi
      rm -f sum.exr img.pfm
    done
    ;;
  memory-bounds)
    # A render that cannot fit ulimit -v is refused before it starts,
    # naming what it needs (it ended in "terminate ... bad_alloc", exit 134);
    # one at the bound of docs/RELIABILITY.md (132 bytes a pixel with --out,
    # plus the program's own 150 MB) is rendered.
    sanitized && skip "a sanitizer build cannot start under ulimit -v"
    exr=0
    have_exr && exr=1  # (it writes an 8 x 8 scene.json of its own)
    scene 4096 4096
    (ulimit -v 600000 && "$bin" --headless --scene scene.json --quiet --frames 1 --out big.png >out.txt 2>err.txt)
    rc=$?
    expect_rc 2
    expect_err "^whisker: not enough memory for rendering 4096 x 4096 pixels: needs about [0-9]+ MB, and the memory limit \(ulimit -v\) leaves [0-9]+ MB$"
    scene 1024 1024
    (ulimit -v $(((150 + 1024 * 1024 * 132 / 1000000 ) * 1000)) &&
      "$bin" --headless --scene scene.json --quiet --frames 1 --depth 0 --threads 2 --out at-bound.png >out.txt 2>err.txt)
    rc=$?
    expect_rc 0
    [ -f at-bound.png ] || fail "the render at the bound wrote nothing"
    if [ $exr = 1 ]; then
      # two_parts PREFIX: the parts 0:1 and 1:2 of scene.json, PREFIX0:1.exr and PREFIX1:2.exr.
      two_parts() {
        local r
        for r in 0:1 1:2; do
          "$bin" --headless --scene scene.json --quiet --samples $r --depth 0 --out-sum "$1$r.exr" >/dev/null 2>&1 ||
            fail "cannot write the part $r"
        done
      }
      two_parts p
      # A merge holds the merged sums and a band of one part (56 bytes a
      # pixel): 1024 x 1024 parts merge under 200 MB (a whole part at a
      # time needed 204 bytes a pixel, 214 MB); 2048 x 2048 do not fit.
      (ulimit -v 200000 && "$bin" merge p0:1.exr p1:2.exr --out m.png >out.txt 2>err.txt)
      rc=$?
      expect_rc 0
      [ -f m.png ] || fail "the streaming merge wrote nothing"
      scene 2048 2048
      two_parts q
      (ulimit -v 200000 && "$bin" merge q0:1.exr q1:2.exr --out m2.png >out.txt 2>err.txt)
      rc=$?
      expect_rc 2
      expect_err "^whisker: merge: not enough memory for merging: needs about"
    fi
    ;;
  part-contents-checked)
    # A part's header may claim anything: an attribute of 2^31-1 bytes had
    # OpenEXR allocate 2.1 GB; FLOAT word channels were converted silently; a
    # 23-digit pass count wrapped. Each is refused naming the field.
    have_exr || skip "this build has no OpenEXR"
    scene 16 16
    run --headless --scene scene.json --quiet --frames 1 --out-sum p.exr
    expect_rc 0
    python3 - <<'PY' || fail "could not craft the parts"
import struct
d = bytearray(open('p.exr', 'rb').read())
def header_end(d):
    at = 8
    while d[at] != 0:
        at = d.index(b'\0', at) + 1          # name
        at = d.index(b'\0', at) + 1          # type
        (size,) = struct.unpack_from('<i', d, at)
        at += 4 + size
    return at + 1
def set_string(d, name, value):
    tag = name.encode() + b'\0string\0'
    k = d.index(tag) + len(tag)
    (old,) = struct.unpack_from('<i', d, k)
    end = header_end(d)
    out = d[:k] + struct.pack('<i', len(value)) + value.encode() + d[k + 4 + old:]
    delta = len(value) - old
    first = struct.unpack_from('<Q', d, end)[0]
    count = (first - end) // 8                 # the line offset table, then the chunks
    for i in range(count):
        at = end + delta + 8 * i
        struct.pack_into('<Q', out, at, struct.unpack_from('<Q', out, at)[0] + delta)
    return out
open('passes.exr', 'wb').write(set_string(d, 'whisker.passes', '1' * 23))
open('comma.exr', 'wb').write(set_string(d, 'whisker.samples', '0:1,'))
open('nan.exr', 'wb').write(set_string(d, 'whisker.seconds', 'nan'))
big = bytearray(d)
tag = b'whisker.scene\0string\0'
struct.pack_into('<i', big, big.index(tag) + len(tag), 2**31 - 1)
open('huge.exr', 'wb').write(big)
flt = bytearray(d)
tag = b'sum.G.hi\0'
struct.pack_into('<i', flt, flt.index(tag) + len(tag), 2)   # pixel type 2 = FLOAT
open('float.exr', 'wb').write(flt)
PY
    for c in "passes:whisker.passes \"11111111111111111111111\" is not a count" \
             "comma:whisker.samples \"0:1,\" is not a list" \
             "nan:whisker.seconds \"nan\" is not a finite number" \
             "huge:header attribute whisker.scene claims 2147483647 bytes" \
             "float:channel sum.G.hi is FLOAT, not UINT"; do
      f=${c%%:*}.exr
      (under_memory_cap 1000 "$bin" merge "$f" --out m.png >out.txt 2>err.txt)
      rc=$?
      expect_rc 2
      expect_err "^whisker: $f: ${c#*:}"
      run --headless --scene scene.json --quiet --frames 2 --resume "$f" --out-sum r.exr
      expect_rc 2
      expect_err "^whisker: --resume $f: ${c#*:}"
    done
    [ ! -e m.png ] && [ ! -e r.exr ] || fail "a damaged part was merged or resumed"
    ;;
  part-features-checked)
    # A part's feature layers (--features): a half missing, a layer of
    # another type, layers that say they hold other samples than the part,
    # layers without the attribute that says which. Each refused in one
    # line naming the file and the layer, by a merge and by a resume.
    have_exr || skip "this build has no OpenEXR"
    scene 16 16
    run --headless --scene scene.json --quiet --frames 2 --features --out-sum p.exr
    expect_rc 0
    run merge p.exr --out-denoised d.png
    expect_rc 0
    rm -f d.png
    python3 - <<'PY' || fail "could not craft the parts"
import struct
d = open('p.exr', 'rb').read()
def swap(name, old, new):
    assert d.count(old) == 1, old
    open(name, 'wb').write(d.replace(old, new))
swap('half.exr', b'feature.odd.albedo.G.lo\0', b'feature.odd.albedo.G.xx\0')
k = d.index(b'feature.depth.Z.hi\0') + len(b'feature.depth.Z.hi\0')
half = bytearray(d)
struct.pack_into('<i', half, k, 1)   # pixel type 1 = HALF
open('type.exr', 'wb').write(half)
swap('count.exr', b'whisker.features\0string\0\3\0\0\0' + b'0:2', b'whisker.features\0string\0\3\0\0\0' + b'0:1')
swap('bare.exr', b'whisker.features\0', b'whisker.featurez\0')
PY
    for c in "half:channel feature.odd.albedo.G.lo missing" \
             "type:channel feature.depth.Z.hi is HALF, not UINT" \
             "count:whisker.features \"0:1\": the feature layers hold other samples than the part's 0:2" \
             "bare:channel odd.sum.R.hi without whisker.features"; do
      f=${c%%:*}.exr
      run merge "$f" --out m.png --out-denoised d.png
      expect_rc 2
      expect_err "^whisker: $f: ${c#*:}"
      [ "$(wc -l <err.txt)" -eq 1 ] || fail "merge $f: $(cat err.txt)"
      run --headless --scene scene.json --quiet --frames 2 --resume "$f" --out-sum r.exr
      expect_rc 2
      expect_err "^whisker: --resume $f: ${c#*:}"
    done
    [ ! -e m.png ] && [ ! -e d.png ] && [ ! -e r.exr ] || fail "a part with damaged feature layers was merged or resumed"
    ;;
  scene-parse-linear)
    # The duplicate-key check rescanned the enclosing array at the end of
    # each object in it: 400,000 objects took 44 s, a file at the cap weeks.
    # 4 Mi values (here empty objects in one array; once a fixed cap) load
    # within a generous time and memory, and so does a file past that old
    # cap: the limit is the machine's memory, estimated up front.
    python3 -c "
n = 4 * 1024 * 1024 - 6
body = ','.join(['{}'] * n)
open('big.json', 'w').write('{\"camera\": {\"width\": 8, \"height\": 8}, \"description\": [' + body + ']}')
open('over.json', 'w').write('{\"camera\": {\"width\": 8, \"height\": 8}, \"description\": [' + body + ',{},{}]}')
" || skip "python3 missing"
    for f in big over; do
      under_memory_cap 1000 timeout -s KILL 90 "$bin" --headless --scene $f.json --quiet --frames 1 --spp 1 \
        --stats s.json >out.txt 2>err.txt
      rc=$?
      [ "$rc" -ne 137 ] || fail "a scene of 4 Mi values ($f.json) took over 90 s to load"
      expect_rc 0
    done
    ;;
  scene-nesting-capped)
    # 60 MB of "[[[[..." took 4.6 GB: nesting deeper than 64 levels is
    # refused naming the line and column, before anything is built.
    python3 -c "
open('deep.json', 'w').write('{\"description\":\n' + '[' * 20000000 + ']' * 20000000 + '}')
d = '{\"description\": ' + '[' * 63 + ']' * 63 + '}'
open('ok.json', 'w').write(d)
open('str.json', 'w').write('{\"description\": \"' + '[' * 100 + '\"}')
" || skip "python3 missing"
    under_memory_cap 400 timeout -s KILL 30 "$bin" --headless --scene deep.json --quiet --frames 1 \
      --stats s.json >out.txt 2>err.txt
    rc=$?
    expect_rc 2
    expect_err "^whisker: deep.json:2:64: arrays and objects nested deeper than 64 levels$"
    for ok in ok str; do
      run --headless --scene $ok.json --quiet --frames 1 --spp 1 --stats s.json
      expect_rc 0
    done
    ;;
  messages-escaped)
    # Every echoed user string is escaped where the line is written: a path
    # with a line break gave 2-3 lines, --out passed a terminal escape
    # through, a scene name (from the file or from a part) was printed raw,
    # "mesh not found" took 4 lines and a FIFO mesh was "not found"; range
    # errors printed the value to 6 digits (1e-320 as 9.99989e-321).
    scene 16 16
    one_line_no_esc() {
      [ "$(wc -l <"${2:-err.txt}")" -le 1 ] || fail "$1: $(wc -l <"${2:-err.txt}") lines: $(head -c 300 "${2:-err.txt}")"
      ! grep -qP '[\x00-\x08\x0b-\x1f\x7f]' "${2:-err.txt}" || fail "$1: a raw control character: $(head -c 300 "${2:-err.txt}" | od -c | head -5)"
    }
    run --headless --scene scene.json --quiet --frames 1 --out $'nodir\x1b]0;pwned\x07/o.png'
    expect_rc 2
    one_line_no_esc "--out with an escape"
    expect_err '^whisker: --out nodir\\x1b\]0;pwned\\x07/o.png: folder'
    mkdir $'a\nb'
    run --headless --scene $'a\nb/x.json' --quiet --frames 1 --stats s.json
    expect_rc 2
    one_line_no_esc "--scene with a line break"
    expect_err '^whisker: .*a\\nb/x.json'
    echo '{"camera": {"width": 16, "height": 16}, "meshes": [{"path": "gone.obj"}]}' >gone.json
    run --headless --scene gone.json --quiet --frames 1 --stats s.json
    expect_rc 2
    one_line_no_esc "mesh not found"
    expect_err '^whisker: gone.json: meshes\[0\].path: mesh "gone.obj" not found \(looked in gone.obj, .*assets/gone.obj\)'
    mkfifo pipe.obj
    echo '{"camera": {"width": 16, "height": 16}, "meshes": [{"path": "pipe.obj"}]}' >pipe.json
    run --headless --scene pipe.json --quiet --frames 1 --stats s.json
    expect_rc 2
    one_line_no_esc "FIFO mesh"
    expect_err '^whisker: pipe.json: meshes\[0\].path: mesh "pipe.obj" is not a regular file \(a FIFO\)$'
    for pair in 'light|"intensity": 1e308|light.intensity: must be in \[0, 1e\+30\], got 1e\+308$' \
                'camera|"fov": 1e-320|camera.fov: must be in \[1, 179\], got 1e-320$' \
                'camera|"fov": 0.1|camera.fov: must be in \[1, 179\], got 0.1$'; do
      IFS='|' read -r obj field want <<<"$pair"
      echo "{\"$obj\": {$field}}" >range.json
      run --headless --scene range.json --quiet --frames 1 --stats s.json
      expect_rc 2
      expect_err "^whisker: range.json: $want"
    done
    printf '{"name": "n\\u001b]0;pwned\\u0007\\nx\\u009b2J", "camera": {"width": 8, "height": 8}}' >named.json
    run --headless --scene named.json --frames 1 --spp 1 --out-float $'o\x1bx.pfm'
    expect_rc 0
    one_line_no_esc "the summary line" out.txt
    ! grep -q $'\xc2\x9b' out.txt || fail "the summary line holds a raw C1 control"
    if have_exr; then
      run --headless --scene named.json --quiet --spp 1 --samples 0:1 --out-sum p.exr
      expect_rc 0
      run merge p.exr --out m.png
      expect_rc 0
      one_line_no_esc "merge's summary (a scene name from a part)" out.txt
      grep -q 'n\\x1b\]0;pwned\\x07\\nx' out.txt || fail "merge's summary: $(cat -v out.txt)"
    fi
    ;;
  list-options-one-reader)
    # --light " 1,2,3", "+1,2,3" and "1, 2, 3" were taken where --intensity
    # refuses " 5" and "+5": every number of a list option is read by the same
    # reader. --edit-light and --edit-after were ignored with --headless.
    scene 8 8
    for opt in --light --split-weights; do
      for bad in ' 1,1,1' '+1,1,1' '1, 1, 1' '1,1,1 ' '1,1' '1,1,1,1' '0x1,1,1' 'nan,1,1' '1,,1' '1e400,1,1'; do
        run --headless --scene scene.json --quiet --frames 1 --stats s.json "$opt" "$bad"
        expect_rc 2
        expect_err "^whisker: $opt "
        [ "$(wc -l <err.txt)" -eq 1 ] || fail "$opt '$bad': more than one line"
      done
      run --headless --scene scene.json --quiet --frames 1 --stats s.json "$opt" '0.5,1e-1,1'
      expect_rc 0
    done
    run --headless --scene scene.json --quiet --frames 1 --stats s.json --light=-1.5,2e3,-0
    expect_rc 0
    run --headless --scene scene.json --quiet --frames 1 --stats s.json --edit-light 1,2,3
    expect_rc 2
    expect_err "^whisker: --edit-light needs the viewer; drop --headless$"
    run --headless --scene scene.json --quiet --frames 1 --stats s.json --edit-after 2
    expect_rc 2
    expect_err "^whisker: --edit-after needs the viewer; drop --headless$"
    run --scene scene.json --frames 1 --edit-after 1 --edit-light ' 1,2,3'
    expect_rc 2
    expect_err "^whisker: --edit-light  1,2,3: expected three finite numbers"
    ;;
  obj-memory-bounded)
    # An OBJ was read whole before its first line was checked: a 3 GB sparse
    # file took 6.3 GB. Its size is checked against the 256 MiB cap before
    # reading, and the lines are checked as they are read, so a bad line
    # early in a large file ends the read there.
    scene 8 8
    truncate -s 3G sparse.obj
    { printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'; } >head.obj
    cp head.obj nul.obj && truncate -s 200M nul.obj
    under_memory_cap 150 timeout -s KILL 20 "$bin" --headless --scene cat --mesh "$PWD/sparse.obj" --quiet \
      --frames 1 --stats s.json >out.txt 2>err.txt
    rc=$?
    expect_rc 2
    expect_err "^whisker: .*sparse.obj: 3221225472 bytes; an OBJ file may have at most 256 MiB$"
    under_memory_cap 150 timeout -s KILL 20 "$bin" --headless --scene cat --mesh "$PWD/nul.obj" --quiet \
      --frames 1 --stats s.json >out.txt 2>err.txt
    rc=$?
    expect_rc 2
    expect_err "^whisker: .*nul.obj:5: binary data, not a text OBJ file$"
    ;;
  *)
    fail "unknown case (see the case list in $0)"
    ;;
esac
echo "PASS [$case]"
