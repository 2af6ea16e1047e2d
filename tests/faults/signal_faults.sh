#!/usr/bin/env bash
# Signals as job wrappers deliver them: `timeout`, Slurm, systemd and a
# shell's kill of a job send the signal to the process and then to its
# process group, two copies within microseconds, which are one request; a
# real second request ends the render at once and says what was written.
#   signal_faults.sh WHISKER_BINARY CASE
# Exit 0 = pass, 1 = fail (with the reason), 77 = skipped (with the reason).
set -uo pipefail
bin=$1 case=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/whisker-signals.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

fail() { echo "FAIL [$case]: $*" >&2; exit 1; }
skip() { echo "SKIP [$case]: $*" >&2; exit 77; }

cat >scene.json <<'JSON'
{"name": "faults", "camera": {"position": [0, 0, 55], "look_at": [0, 0, 0], "width": 16, "height": 16},
 "light": {"position": [-10, 20, 40]},
 "spheres": [{"center": [0, -1000, 0], "radius": 990, "material": {"type": "diffuse", "albedo": [0, 0, 1]}},
             {"center": [0, 0, 0], "radius": 10, "material": {"type": "diffuse", "albedo": [1, 1, 1]}}]}
JSON
# A render that runs until stopped, one thread, a progress line every 0.01 s
# (stderr is a file) from which to see that passes are complete.
render=(--headless --scene scene.json --frames 1000000 --spp 1 --threads 1 --progress 0.01)
outputs() { echo "--out img-$1.png --stats stats-$1.json"; }

# The outputs of interrupted renders, img-RUN.png and stats-RUN.json: whole
# PNGs (every chunk's CRC and the pixels' zlib stream checked), stats of
# some passes. One python3 for all the runs: its start is most of the time.
check_outputs() {
  python3 - "$@" <<'PY' || fail "$(cat check.txt 2>/dev/null)"
import json, struct, sys, zlib
def bad(why):
    open('check.txt', 'w').write(why); sys.exit(1)
def check(png, stats):
    try:
        data = open(png, 'rb').read()
    except OSError as e:
        bad(f'{png}: {e.strerror}')
    if data[:8] != b'\x89PNG\r\n\x1a\n': bad(f'{png} is not a PNG')
    pos, idat, kinds = 8, b'', []
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if struct.unpack('>I', data[pos + 8 + n:pos + 12 + n])[0] != zlib.crc32(kind + body):
            bad(f'{png}: chunk {kind} fails its CRC')
        kinds.append(kind)
        idat += body if kind == b'IDAT' else b''
        pos += 12 + n
    if kinds[-1:] != [b'IEND']: bad(f'{png} ends without IEND')
    w, h = struct.unpack('>II', data[16:24])
    if len(zlib.decompress(idat)) != h * (1 + 3 * w): bad(f'{png}: pixel data cut short')
    passes = json.load(open(stats))['passes']
    if not 1 <= passes < 1000000: bad(f'{stats} says {passes} passes')
for run in sys.argv[1:]:
    check(f'img-{run}.png', f'stats-{run}.json')
PY
}
# Run RUN's exit code ($rc) and stderr (err-RUN.txt): CODE, and the line
# saying what was written; no temporary file.
expect_interrupted() {
  local code=$1 run=$2
  [ "$rc" -eq "$code" ] || fail "run $run: exit $rc, expected $code; stderr: $(tail -c 400 "err-$run.txt")"
  grep -q "interrupted: wrote the" "err-$run.txt" ||
    fail "run $run: no line saying what was written; stderr: $(tail -c 400 "err-$run.txt")"
  [ -z "$(find . -name '.*.tmp-*')" ] || fail "run $run: temporary files left behind"
}

# Waits until the progress in FILE shows two samples per pixel (so a pass
# is published, and the handlers are installed); $pid must still run.
wait_for_passes() {
  local i
  for i in $(seq 500); do
    grep -qsE '^faults: ([2-9]|[1-9][0-9]+)\.[0-9]/' "$1" && return 0
    kill -0 "$pid" 2>/dev/null || fail "the render ended by itself: $(cat "$1")"
    sleep 0.01
  done
  fail "no pass in 5 s: $(cat "$1")"
}

case $case in
  wrapper-signal-copies-one-request)
    # SIGTERM to the process, then to its process group, back to back, as
    # `timeout` sends it: one request, so every run writes its passes and
    # exits 143. (Before, the second copy often ended it with nothing
    # written and nothing said.)
    set -m  # each background job in a process group of its own, pgid = pid
    for run in $(seq 20); do
      # shellcheck disable=SC2046
      "$bin" "${render[@]}" $(outputs "$run") >/dev/null 2>"err-$run.txt" &
      pid=$!
      wait_for_passes "err-$run.txt"
      kill -TERM "$pid"
      kill -TERM -- "-$pid"
      wait "$pid"
      rc=$?
      expect_interrupted 143 "$run"
    done
    check_outputs $(seq 20)
    ;;
  under-timeout)
    # The same under GNU timeout itself (--preserve-status: its exit code is
    # the render's).
    command -v timeout >/dev/null || skip "no timeout(1) here"
    for run in 1 2 3 4; do
      # shellcheck disable=SC2046
      timeout --preserve-status 0.5 "$bin" "${render[@]}" $(outputs "$run") >/dev/null 2>"err-$run.txt"
      rc=$?
      expect_interrupted 143 "$run"
    done
    check_outputs 1 2 3 4
    ;;
  second-request-stops-at-once | same-signal-later-is-a-second-request)
    # A render whose summary line is stuck behind a full stdout pipe (a
    # reader that stopped reading), after its images are written and before
    # its stats: SIGTERM, then 1.5 s later a second request (SIGINT; or
    # SIGTERM again, no copy that late) ends it at once, exit 128 + the
    # second's number, saying what was and was not written.
    second=INT
    [ "$case" = same-signal-later-is-a-second-request ] && second=TERM
    python3 - "$bin" "$second" <<'PY' || exit 1
import fcntl, os, signal, subprocess, sys, time
bin, second = sys.argv[1], sys.argv[2]
def fail(why):
    print(f'FAIL [SIG{second} 1.5 s after SIGTERM]: {why}; stderr: '
          + open('err.txt').read()[-400:], file=sys.stderr)
    sys.exit(1)
for f in ('img.png', 'img.pfm', 'stats.json'):
    if os.path.exists(f): os.remove(f)
r, w = os.pipe()
fcntl.fcntl(w, fcntl.F_SETFL, os.O_NONBLOCK)
for size in (4096, 1):  # full to the last byte
    try:
        while True: os.write(w, b'x' * size)
    except BlockingIOError:
        pass
fcntl.fcntl(w, fcntl.F_SETFL, 0)
p = subprocess.Popen([bin, '--headless', '--scene', 'scene.json', '--quiet', '--frames', '2',
                      '--spp', '1', '--threads', '1', '--out', 'img.png', '--out-float', 'img.pfm',
                      '--stats', 'stats.json'], stdout=w, stderr=open('err.txt', 'w'))
os.close(w)
deadline = time.monotonic() + 5
while not os.path.exists('img.pfm'):
    if p.poll() is not None: fail(f'ended by itself, exit {p.returncode}')
    if time.monotonic() > deadline: fail('img.pfm not written in 5 s')
    time.sleep(0.01)
time.sleep(0.2)
if p.poll() is not None: fail(f'ended with stdout full, exit {p.returncode}')
p.send_signal(signal.SIGTERM)
time.sleep(1.5)
if p.poll() is not None: fail(f'ended after the first request, exit {p.returncode}')
p.send_signal(getattr(signal, 'SIG' + second))
try:
    rc = p.wait(timeout=1)
except subprocess.TimeoutExpired:
    p.kill(); fail('still running 1 s after the second request')
code = 128 + getattr(signal, 'SIG' + second)
if rc != code: fail(f'exit {rc}, expected {code}')
want = ('whisker: second request to stop (SIG' + second +
        (' again' if second == 'TERM' else ' after SIGTERM') +
        '): stopped at once; wrote img.png, img.pfm; not written: stats.json\n')
if want not in open('err.txt').read(): fail('no line ' + repr(want))
if os.path.exists('stats.json'): fail('stats.json written')
if [f for f in os.listdir('.') if '.tmp-' in f]: fail('temporary files left behind')
PY
    ;;
  *) fail "no such case" ;;
esac
exit 0
