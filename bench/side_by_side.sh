#!/usr/bin/env bash
# The comparison figures in one run, each comparison with the other program run
# beside Whisker in this same script (never a constant from a document):
#   1. the cat target at every scale (bench/cat_target.sh): time to the
#      error the report's program has at 1024 spp, at 1, 2, 4, 8 and 16 px,
#      against that program's time; the headline is the worst scale, and the
#      run fails when the defaults lose to the estimator without light connections;
#   2. rays per second against Embree, one thread, RUNS runs of each ray set,
#      the two sets alternating (Embree's repetitions alternate with
#      Whisker's inside each run);
#   3. fig 8 at the report's settings beside the report's program
#      (bench/render_times.sh);
#   4. the viewer's passes per second and UI frame time on the cat at one
#      path per sample (needs xvfb-run; skipped without it).
#
#   bench/side_by_side.sh          # ~21 minutes on the 2-core machine; quiet machine please
#
# Knobs: RUNS (5), RAYS (a folder holding cat_primary.rays and
# cat_diffuse.rays; default: the sets `whisker-bench make-rays` writes into
# OUT), WHISKER_BUILD (build), and
# those of the two scripts it calls (BEST_SPP, REPORT_PROGRAM_DIR, ...).
# Prints one markdown table at the end; the raw outputs stay in OUT
# ($BUILD/side-by-side).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${WHISKER_BUILD:-$ROOT/build}
RUNS=${RUNS:-5}
OUT=$BUILD/side-by-side
mkdir -p "$OUT"
cmake --build "$BUILD" -j 2 --target whisker whisker-bench whisker-compare >/dev/null
if [ -z "${RAYS:-}" ]; then
  RAYS=$OUT/rays
  mkdir -p "$RAYS"
  "$BUILD/bench/whisker-bench" make-rays "$RAYS" >/dev/null
fi

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"

echo "== 1. the cat target at every scale"
cat_status=0
WHISKER_BUILD=$BUILD "$ROOT/bench/cat_target.sh" | tee "$OUT/cat_target.txt" || cat_status=$?

echo "== 2. rays against Embree, $RUNS runs"
for ((k = 1; k <= RUNS; k++)); do
  for set in primary diffuse; do
    "$BUILD/bench/whisker-bench" rays "$RAYS/cat_$set.rays" --accel sah --json --reps 9 --threads 1 \
      >"$OUT/rays-$set-$k.json"
  done
done

echo "== 3. fig 8 at the report's settings"
WHISKER_BUILD=$BUILD "$ROOT/bench/render_times.sh" 3 | tee "$OUT/render_times.txt"

echo "== 4. the viewer"
if command -v xvfb-run >/dev/null 2>&1; then
  LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 1280x800x24" "$BUILD/whisker" --scene cat \
    --split 1 --connect off --frames 60 --screenshot "$OUT/viewer.png" 2>&1 | tail -1 | tee "$OUT/viewer.txt"
else
  echo "no xvfb-run: skipped" | tee "$OUT/viewer.txt"
fi

python3 - "$OUT" "$RUNS" <<'PY'
import json, re, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
cat = open(f"{out}/cat_target.txt").read()
worst = re.search(r"worst scale of defaults: (\d+) px, (\d+) spp in ([\d.]+) s -> ([\d.]+)x less than the report program \((\d+) s", cat)
checked = re.search(r"headline \(checked render\): (\d+) spp in ([\d.]+) s reach the target at every scale -> ([\d.]+)x less than the report program \((\d+) s", cat)
rows = ["| figure | report's program / Embree | Whisker | ratio | aim |", "|---|---|---|---|---|"]
if checked:
    spp, secs, ratio, report = checked.groups()
    rows.append(f"| cat target at every scale (a render that reaches the report program's 1024-spp error at 1-16 px) | {report} s | {spp} spp, {secs} s | {ratio}x | 100x |")
elif worst:
    k, spp, secs, ratio, report = worst.groups()
    rows.append(f"| cat target at the worst scale ({k} px; interpolated, no check render reached the target) | {report} s | {spp} spp, {secs} s | {ratio}x | 100x |")
else:
    rows.append("| cat target | | no figure | | 100x |")
for name, aim in (("primary", "1.2x"), ("diffuse", "1.1x")):
    rs = [json.load(open(f"{out}/rays-{name}-{k}.json")) for k in range(1, runs + 1)]
    same = all(r["hits"] == r["embree_hits"] for r in rs)
    ratios = [r["ratio"] for r in rs]
    w = [r["mrays_per_s_1thread"] for r in rs]
    e = [r["embree_mrays_per_s_1thread"] for r in rs]
    rows.append(f"| {name} rays, 1 thread | {min(e):.1f}-{max(e):.1f} Mrays/s | {min(w):.1f}-{max(w):.1f} Mrays/s | "
                f"{statistics.median(ratios):.3f}x median of {runs} ({', '.join(f'{x:.3f}' for x in ratios)})"
                f"{'' if same else ' HITS DIFFER'} | {aim} |")
times = open(f"{out}/render_times.txt").read()
report = re.search(r"fig 8 at 1024 spp, \d+ threads: ([\d.]+) s", times)
for label, name, aim in (("fig 8 at the report's settings (1024 one-path samples, its independent random numbers)", "cat \\(fig 8\\)", "12x"),
                         ("fig 8 with Whisker's Sobol points (half the error at equal samples)", "cat \\(fig 8, Sobol\\)", "")):
    fig8 = re.search(r"\| " + name + r" \| 1024 \| ([\d.]+) \|", times)
    if fig8 and report:
        w, r = float(fig8.group(1)), float(report.group(1))
        rows.append(f"| {label} | {r:.1f} s | {w:.1f} s | {r / w:.1f}x | {aim} |")
viewer = open(f"{out}/viewer.txt").read().strip()
m = re.search(r"([\d.]+) passes/s; UI \d+ frames, mean ([\d.]+) ms, p95 ([\d.]+) ms", viewer)
if m:
    rows.append(f"| viewer, cat 512x512, one path per sample per pass | - | {m.group(1)} passes/s, UI mean {m.group(2)} ms, p95 {m.group(3)} ms | | 10 passes/s, 20 ms |")
print("\n".join(rows))
PY
exit "$cat_status"
