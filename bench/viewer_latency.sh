#!/usr/bin/env bash
# How fast an edit shows in the real viewer window (under Xvfb, software GL).
#
#   bench/viewer_latency.sh [build/whisker] [repeats] [scene]
#
# For each edit (a light move, a toggle of anti-aliasing, a camera orbit),
# made by the viewer's own script after 2 passes (--edit-after, the same path
# as the panel), the viewer's event log (--edit-log) gives, from the frame
# that made the edit:
#   first image: the first frame drawn after its swap that shows the new
#                settings (a quick pass, ProgressiveRenderer::set_quick_passes);
#   first pass:  the first frame with a full pass of the new settings;
#   5 % noise:   the first frame whose own passes' noise figure is <= 5 %.
# Then a mouse drag through xdotool (60 moves a second for 3 s on the
# image, one xdotool process): how many different camera positions the
# window showed per second, of how many the mouse made,
# and how far behind the mouse the image was (time
# from the frame that made an edit to the first frame showing it).
# Medians over the repeats; the machine's load is printed with them.
set -u
bin=${1:-build/whisker}
repeats=${2:-3}
scene=${3:-cat}
frames=${FRAMES:-14}
command -v xvfb-run >/dev/null || { echo "needs xvfb-run"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export LIBGL_ALWAYS_SOFTWARE=1

analyse() {  # log -> "first_image first_pass noise5" in ms (or -)
  python3 - "$1" <<'PY'
import sys
edit_t, gen, first_img, first_pass, noise5 = None, None, None, None, None
edits = 0
for line in open(sys.argv[1]):
    parts = line.split()
    if parts[0] not in ("edit", "frame"): continue  # message, ask, readout lines
    kv = dict(p.split("=", 1) for p in parts[1:])
    if parts[0] == "edit":
        edits += 1
        if edits == 2:
            edit_t, gen = float(kv["t"]), kv["gen"]
        continue
    if edit_t is None: continue
    t = float(kv["t"])
    if first_img is None and kv["shown_gen"] == gen: first_img = t - edit_t
    if first_pass is None and kv["own_gen"] == gen and int(kv["own_passes"]) >= 1: first_pass = t - edit_t
    if noise5 is None and kv["own_gen"] == gen and kv["rse"] not in ("nan", "inf") and float(kv["rse"]) <= 0.05:
        noise5 = t - edit_t
f = lambda v: "-" if v is None else "%.0f" % (v * 1000)
print(f(first_img), f(first_pass), f(noise5))
PY
}

median() { python3 -c "import sys,statistics as s; v=[float(x) for x in sys.argv[1:] if x!='-']; print('%.0f'%s.median(v) if v else '-')" "$@"; }

echo "scene $scene, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $repeats repeats"
printf "%-8s %14s %14s %14s\n" edit "first image ms" "first pass ms" "5% noise ms"
for edit in "--edit-light 10,25,30" "--edit-toggle aa" "--edit-orbit 0.3,0.1"; do
  a=() b=() c=()
  for r in $(seq "$repeats"); do
    log="$dir/e$r.log"
    xvfb-run -a -s "-screen 0 1600x900x24" "$bin" --scene "$scene" --frames "$frames" \
      --edit-after 2 $edit --edit-log "$log" >/dev/null 2>"$dir/err" || { cat "$dir/err"; continue; }
    read -r x y z < <(analyse "$log")
    a+=("$x") b+=("$y") c+=("$z")
  done
  name=$(echo "$edit" | sed 's/--edit-\([a-z]*\).*/\1/')
  printf "%-8s %14s %14s %14s   (runs: %s | %s | %s)\n" "$name" "$(median "${a[@]}")" \
    "$(median "${b[@]}")" "$(median "${c[@]}")" "${a[*]}" "${b[*]}" "${c[*]}"
done

# The drag: an interactive window, 180 mouse moves over 3 s with button 1 held.
cat >"$dir/drag.sh" <<'INNER'
bin=$1 scene=$2 log=$3
"$bin" --scene "$scene" --edit-log "$log" >/dev/null 2>&1 &
pid=$!
wid=$(timeout 60 xdotool search --sync --onlyvisible --name '^Whisker' | head -1)
sleep 3
xdotool mousemove --window "$wid" 200 300; sleep 0.3; xdotool mousedown 1; sleep 0.1
# One xdotool process for the whole drag (a process per move would cap the
# rate at what starting xdotool costs): a pixel further every 1/60 s.
moves=()
for k in $(seq 180); do moves+=(mousemove --window "$wid" $((200 + k)) 300 sleep 0.0167); done
xdotool "${moves[@]}"
xdotool mouseup 1; sleep 1
xdotool key --window "$wid" Escape
wait $pid
INNER
if command -v xdotool >/dev/null; then
  rates=() lags=() inputs=()
  for r in $(seq "$repeats"); do
    xvfb-run -a -s "-screen 0 1600x900x24" bash "$dir/drag.sh" "$bin" "$scene" "$dir/d$r.log"
    read -r rate lag input < <(python3 - "$dir/d$r.log" <<'PY'
import sys, statistics
edits, frames = {}, []
for line in open(sys.argv[1]):
    parts = line.split()
    if parts[0] not in ("edit", "frame"): continue  # message, ask, readout lines
    kv = dict(p.split("=", 1) for p in parts[1:])
    if parts[0] == "edit": edits[kv["gen"]] = float(kv["t"])
    else: frames.append((float(kv["t"]), kv["shown_gen"]))
gens = sorted(edits, key=lambda g: edits[g])[1:]  # the drag's edits (not the first load)
if len(gens) < 2: print("- - -"); sys.exit()
t0, t1 = edits[gens[0]], edits[gens[-1]]
shown = {}
for t, g in frames:
    if g in edits and g not in shown: shown[g] = t
during = [g for g in shown if t0 <= shown[g] <= t1 + 0.2 and g in gens]
rate = len(during) / max(t1 - t0, 1e-3)
lag = statistics.median(shown[g] - edits[g] for g in during) if during else float("nan")
print("%.1f %.0f %.1f" % (rate, lag * 1000, (len(gens) - 1) / max(t1 - t0, 1e-3)))
PY
)
    rates+=("$rate") lags+=("$lag") inputs+=("$input")
  done
  echo "drag: $(median "${rates[@]}") camera positions shown per second of $(median "${inputs[@]}") made, image $(median "${lags[@]}") ms behind the mouse (runs: ${rates[*]} | ${inputs[*]} | ${lags[*]})"
fi
