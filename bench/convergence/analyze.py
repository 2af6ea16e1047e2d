#!/usr/bin/env python3
"""Turns the runs of bench/speed_vs_error.sh into results.csv, gnuplot
scripts (one log-log plot of MSE against seconds per scene) and the markdown
tables for docs/PERFORMANCE.md (printed on stdout).

    analyze.py OUT_DIR

Reads OUT_DIR/runs/*.json (whisker --stats and whisker-compare --json files)
and OUT_DIR/machine.json. Only the standard library: it runs wherever the
build does.

Per spp count, MSE (the worst scale's, worst_scale_mse) is the mean over seeds and time the median over seeds (a
load spike from another process on the shared machine moves a mean, hardly a
median). Interpolation is linear in log-log between these points;
outside the measured range it extrapolates along a least-squares line through
the three nearest points and says so ("extrap.").
"""
import csv
import glob
import json
import math
import os
import re
import sys
from collections import defaultdict

# The report's program's time for the cat at 1024 spp, 512x512, measured beside
# Whisker in the same run (bench/cat_target.sh prints it); without it the
# study states no ratio to that program.
REPORT_PROGRAM_CAT_SECONDS = (float(os.environ["REPORT_PROGRAM_SECONDS"])
                              if os.environ.get("REPORT_PROGRAM_SECONDS") else None)
TARGET_FACTOR = 100


def worst_scale_mse(cmp):
    """The error a person sees: the largest of k^2 x MSE after box-filtering
    by k (whisker-compare's mse_by_scale; k^2 x MSE_k equals the pixel MSE
    for independent pixel errors, and exceeds it for blotches), so an
    estimator that moves error into blotches gains nothing here. Without
    the scales (an old compare file): the pixel MSE."""
    scales = cmp.get("mse_by_scale") or {}
    return max([cmp["mse"]] + [int(k) ** 2 * v for k, v in scales.items() if v == v])


def load(path):
    with open(path) as f:
        return json.load(f)


def fit(xs, ys):
    """Least-squares line y = a + b x."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    return my - b * mx, b


def log_points(xs, ys):
    """The logs of the points with both coordinates positive: CPU times of
    the shortest renders can read 0 (clock granularity)."""
    xs, ys = zip(*[(a, b) for a, b in zip(xs, ys) if a > 0 and b > 0])
    return [math.log(v) for v in xs], [math.log(v) for v in ys]


def loglog_at(xs, ys, x):
    """y at x on the log-log polyline through (xs, ys) (xs increasing).
    Returns (y, extrapolated)."""
    lx, ly = log_points(xs, ys)
    t = math.log(x)
    for i in range(len(lx) - 1):
        if lx[i] <= t <= lx[i + 1]:
            w = (t - lx[i]) / (lx[i + 1] - lx[i]) if lx[i + 1] > lx[i] else 0.0
            return math.exp(ly[i] + w * (ly[i + 1] - ly[i])), False
    pts = list(zip(lx, ly))
    pts = pts[-3:] if t > lx[-1] else pts[:3]
    a, b = fit([p[0] for p in pts], [p[1] for p in pts])
    return math.exp(a + b * t), True


def x_at_y(xs, ys, y):
    """The x where the log-log polyline reaches y, ys decreasing in xs.
    Returns (x, extrapolated)."""
    lx, ly = log_points(xs, ys)
    t = math.log(y)
    for i in range(len(lx) - 1):
        hi, lo = ly[i], ly[i + 1]
        if lo <= t <= hi and hi > lo:
            w = (hi - t) / (hi - lo)
            return math.exp(lx[i] + w * (lx[i + 1] - lx[i])), False
    pts = list(zip(lx, ly))
    pts = pts[-3:] if t < min(ly) else pts[:3]
    a, b = fit([p[0] for p in pts], [p[1] for p in pts])
    return math.exp((t - a) / b), True


def median(v):
    v = sorted(v)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def cpu_of(stats_path):
    """User + system CPU seconds (GNU time) of that render, or None."""
    try:
        u, s = open(stats_path + ".cpu").read().split()[-2:]
        return float(u) + float(s)
    except (OSError, ValueError):
        return None


def fmt(v, digits=3):
    if v is None:
        return "-"
    if v == 0:
        return "0"
    if abs(v) >= 1e5 or abs(v) < 1e-3:
        return f"{v:.{digits - 1}e}"
    return f"{v:.{digits}g}"


def mark(v, extrap, digits=3):
    return fmt(v, digits) + (" (extrap.)" if extrap else "")


def main():
    out = sys.argv[1]
    runs = os.path.join(out, "runs")
    machine = load(os.path.join(out, "machine.json"))
    run_info = load(os.path.join(out, "run.json")) if os.path.exists(os.path.join(out, "run.json")) else {}
    res = machine["res"]

    # --- results.csv --------------------------------------------------------
    rows = []
    pat = re.compile(r"^(.+)-(report|best)-(\d+)-(\d+)\.stats\.json$")
    for path in glob.glob(os.path.join(runs, "*.stats.json")):
        m = pat.match(os.path.basename(path))
        if not m:
            continue
        scene, method, spp, seed = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        base = path[: -len(".stats.json")]
        st = load(path)
        cmp = load(base + ".cmp.json")
        load1 = open(base + ".load").read().strip() if os.path.exists(base + ".load") else ""
        s = st["settings"]
        rows.append({
            "scene": scene, "method": method,
            "sampler": s.get("sampler", ""), "zero_cutoff": "on" if s.get("zero_cutoff") else "off",
            "split": ",".join(str(k) for k in s.get("split", [1])),
            "split_weights": ",".join(f"{w:g}" for w in s.get("split_weights", [1, 1, 1])),
            "aa": "on" if s["aa"] else "off", "indirect": "on" if s["indirect"] else "off",
            "fresnel": "on" if s["fresnel"] else "off", "max_depth": s["max_depth"],
            "width": st["width"], "height": st["height"], "threads": st["threads"],
            "spp": spp, "seed": seed, "seconds": st["seconds"], "cpu_seconds": cpu_of(path),
            "rays": st["rays"],
            "mse": worst_scale_mse(cmp), "mse_pixel": cmp["mse"],
            "rmse": cmp["rmse"], "rel_mse": cmp["rel_mse"],
            "mean_diff_z": cmp["mean_diff_z"], "load1": load1,
        })
    rows.sort(key=lambda r: (r["scene"], r["spp"], r["seed"], r["method"]))
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    # --- means over seeds ---------------------------------------------------
    groups = defaultdict(list)
    for r in rows:
        groups[(r["scene"], r["method"], r["spp"])].append(r)
    curves = defaultdict(lambda: {"spp": [], "t": [], "cpu": [], "mse": [], "rel": []})
    flags = {}
    for (scene, method, spp), rs in sorted(groups.items(), key=lambda kv: kv[0]):
        c = curves[(scene, method)]
        c["spp"].append(spp)
        c["t"].append(median([r["seconds"] for r in rs]))
        cpus = [r["cpu_seconds"] for r in rs if r["cpu_seconds"] is not None]
        # CPU seconds / threads: the render time on an otherwise idle machine,
        # if the threads scale perfectly (they share nothing but tiles).
        c["cpu"].append(median(cpus) / rs[0]["threads"] if len(cpus) == len(rs) else None)
        c["mse"].append(sum(r["mse"] for r in rs) / len(rs))
        c["rel"].append(sum(r["rel_mse"] for r in rs) / len(rs))
        flags[(scene, method)] = (f"--sampler {rs[0]['sampler']} --zero-cutoff {rs[0]['zero_cutoff']}"
                                   f" --split {rs[0]['split']}"
                                   + (f" --split-weights {rs[0]['split_weights']}"
                                      if rs[0]["split_weights"] != "1,1,1" else ""))
    order = ["three-balls-fresnel", "indirect", "cat", "closed-sphere"]
    scenes = sorted({k[0] for k in curves}, key=lambda s: order.index(s) if s in order else 99)
    res_of = {r["scene"]: r["width"] for r in rows}
    loads = [float(r["load1"]) for r in rows if r["load1"]]

    # --- gnuplot ------------------------------------------------------------
    for scene in scenes:
        dat = os.path.join(out, f"{scene}.dat")
        with open(dat, "w") as f:
            for method in ("report", "best"):
                c = curves[(scene, method)]
                f.write(f"# {method}: spp seconds mse\n")
                for spp, t, e in zip(c["spp"], c["t"], c["mse"]):
                    f.write(f"{spp} {t:.6g} {e:.6g}\n")
                f.write("\n\n")
            for method in ("report", "best"):
                f.write(f"# {method} per seed: seconds mse\n")
                for r in rows:
                    if r["scene"] == scene and r["method"] == method:
                        f.write(f"{r['seconds']:.6g} {r['mse']:.6g}\n")
                f.write("\n\n")
        png = os.path.join(out, f"{scene}.png")
        fr, fb = flags[(scene, "report")], flags[(scene, "best")]
        with open(os.path.join(out, f"{scene}.gp"), "w") as f:
            f.write(f"""set terminal pngcairo size 720,520 noenhanced font ',10'
set output '{png}'
set title "{scene}, {res_of[scene]}x{res_of[scene]}: MSE (mean of {len(machine['seeds'].split())} seeds) against render time (median); 1..{max(curves[(scene, 'report')]['spp'])} spp"
set logscale xy
set xlabel 'seconds (render time, --stats)'
set ylabel 'worst-scale MSE: max over k = 1..16 px of k^2 MSE_k (radiance / 255^2.2)'
set grid
set key top right
plot '{dat}' index 0 using 2:3 with linespoints lw 2 pt 7 title "report's method ({fr})", \\
     '{dat}' index 1 using 2:3 with linespoints lw 2 pt 5 title "Whisker best ({fb})", \\
     '{dat}' index 2 using 1:2 with points pt 1 lc 1 notitle, \\
     '{dat}' index 3 using 1:2 with points pt 1 lc 2 notitle
""")

    # --- tables -------------------------------------------------------------
    p = print
    p(f"Resolution {res}x{res} (same camera and field of view as 512x512; closed-sphere "
      f"{machine.get('closed_res', res)}x{machine.get('closed_res', res)}), "
      f"{machine['threads']} threads, seeds {machine['seeds']}, commit {machine['commit']}"
      f"{' + uncommitted changes' if machine.get('dirty') else ''}, {machine['date']}; "
      f"{machine['cpu']}, nproc={machine['nproc']}; load average 1 min at the runs: "
      f"{min(loads):.1f} to {max(loads):.1f} (mean {sum(loads) / len(loads):.1f})." if loads else "")
    if run_info:
        p(f"Whole run: {run_info['wall_seconds']} s of wall time.")
    p()
    p("MSE, relMSE on radiance / 255^2.2 (1 = display white), mean over seeds, "
      "against the reference; seconds = render time from --stats, median over seeds; "
      "CPU = (user + system CPU seconds) / threads, median over seeds; "
      "efficiency = 1 / (MSE x seconds); slope = least-squares "
      "slope of log MSE against log seconds over all counts.")
    p()
    p("| scene | method | flags | s per spp | CPU s per spp | spp | seconds | MSE | RMSE | relMSE | efficiency | slope |")
    p("|---|---|---|---|---|---|---|---|---|---|---|---|")
    summary = {}
    for scene in scenes:
        common_max = min(max(curves[(scene, m)]["spp"]) for m in ("report", "best"))
        common_max = min(common_max, 256)
        for method in ("report", "best"):
            c = curves[(scene, method)]
            i = c["spp"].index(common_max)
            t, e, rel, cpu = c["t"][i], c["mse"][i], c["rel"][i], c["cpu"][i]
            a, b = fit([math.log(v) for v in c["t"]], [math.log(v) for v in c["mse"]])
            summary[(scene, method)] = (t, e, 1.0 / (e * t), common_max)
            p(f"| {scene} | {'report' if method == 'report' else 'Whisker best'} | `{flags[(scene, method)]}` | "
              f"{fmt(t / common_max)} | {fmt(cpu / common_max if cpu else None)} | {common_max} | {fmt(t)} | {fmt(e)} | {fmt(math.sqrt(e))} | {fmt(rel)} | "
              f"{fmt(1.0 / (e * t))} | {b:.2f} |")
    p()
    p("Equal-time error (at the time Whisker best takes for 256 spp), time to reach a stated "
      "error (the report's method's MSE at 256 spp), and the efficiency ratio; the last column "
      "is the same speed-up measured in CPU time:")
    p()
    p("| scene | equal time (s) | MSE report | MSE best | error ratio | stated MSE | time report (s) | time best (s) | speed-up | efficiency ratio | speed-up (CPU time) |")
    p("|---|---|---|---|---|---|---|---|---|---|---|")
    for scene in scenes:
        cr, cb = curves[(scene, "report")], curves[(scene, "best")]
        tb, eb, effb, _ = summary[(scene, "best")]
        tr, er, effr, _ = summary[(scene, "report")]
        er_at, ex1 = loglog_at(cr["t"], cr["mse"], tb)
        tb_reach, ex2 = x_at_y(cb["t"], cb["mse"], er)
        cpu_speedup = "-"
        if None not in cr["cpu"] and None not in cb["cpu"]:
            i = cr["spp"].index(summary[(scene, "report")][3])
            cb_reach, ex3 = x_at_y(cb["cpu"], cb["mse"], er)
            cpu_speedup = mark(cr["cpu"][i] / cb_reach, ex3) + "x"
        p(f"| {scene} | {fmt(tb)} | {mark(er_at, ex1)} | {fmt(eb)} | {fmt(er_at / eb)} | {fmt(er)} | "
          f"{fmt(tr)} | {mark(tb_reach, ex2)} | {fmt(tr / tb_reach)}x | {fmt(effb / effr)}x | {cpu_speedup} |")
    p()

    # --- agreement of the converged images ----------------------------------
    p(f"Converged images: each method at {machine['agree_spp']} spp (seeds 2000 and 3000) against "
      f"each other and against the reference (Whisker best, "
      f"{machine['ref_spp']} spp, seed 1000; closed-sphere: its exact image). If both are unbiased "
      "the MSE between two images is their own noise, C_a / N_a + C_b / N_b with C = n x MSE(n) "
      "from the study at 256 spp (for Sobol an overestimate if its error keeps falling faster "
      "than 1/n); z = mean signed difference over its standard error.")
    p()
    p("| scene | images | MSE observed | MSE expected from noise | ratio | mean difference (% of mean) | z |")
    p("|---|---|---|---|---|---|---|")
    for scene in scenes:
        if (scene, "best") not in summary:
            continue
        _, eb, _, n = summary[(scene, "best")]
        _, er, _, _ = summary[(scene, "report")]
        exact = scene == "closed-sphere"
        var_ref = 0.0 if exact else eb * n / machine["ref_spp"]
        c_rep = n * max(er - var_ref, 0.0)
        c_best = n * max(eb - var_ref, 0.0)
        na = machine["agree_spp"]
        pairs = [("agree-pair", f"report {na} vs best {na}", c_rep / na + c_best / na),
                 ("agree", f"report {na} vs reference", c_rep / na + var_ref),
                 ("agree-best", f"best {na} vs reference", c_best / na + var_ref)]
        for key, label, expected in pairs:
            path = os.path.join(runs, f"{key}-{scene}.json")
            if not os.path.exists(path):
                continue
            a = load(path)
            p(f"| {scene} | {label} | {fmt(a['mse'])} | {fmt(expected)} | {fmt(a['mse'] / expected)} | "
              f"{100 * a['mean_diff'] / a['mean_reference']:+.3f} % | {a['mean_diff_z']:+.2f} |")
    zs = [r["mean_diff_z"] for r in rows
          if r["scene"] == "closed-sphere" and r["method"] == "best" and r["spp"] >= 64]
    if zs:
        p()
        p("closed-sphere, Whisker best against the exact image at 64 to 256 spp: z of the mean "
          f"difference over {len(zs)} renders: {', '.join(f'{z:+.2f}' for z in zs)}.")
    p()

    # --- the cat target -----------------------------------------------------
    if ("cat", "report") in curves and 1024 in curves[("cat", "report")]["spp"]:
        cr, cb = curves[("cat", "report")], curves[("cat", "best")]
        i = cr["spp"].index(1024)
        e1024, t1024 = cr["mse"][i], cr["t"][i]
        t_best, ex_t = x_at_y(cb["t"], cb["mse"], e1024)
        spp_best, ex_s = x_at_y(cb["spp"], cb["mse"], e1024)
        scale = (512 / res) ** 2
        lines = [f"Cat target (issue 6, section 4), estimated from the study at {res}x{res} (a "
                 "stand-in: a 64x64 pixel averages 64 times the area, so its error per sample "
                 "differs; the target itself is measured at the issue's 512x512 by "
                 "bench/cat_target.sh, docs/PERFORMANCE.md):",
                 "",
                 f"- error of the report's method at 1024 spp: MSE {fmt(e1024)} "
                 f"(in Whisker with `--sampler independent --zero-cutoff off`, the report's estimator), "
                 f"{fmt(t1024)} s here;",
                 f"- Whisker best reaches it at {mark(spp_best, ex_s)} spp, {mark(t_best, ex_t)} s here;",
                 f"- scaled by the pixel ratio ({scale:.0f}x) to 512x512: {fmt(t_best * scale)} s"]
        fr = {m: os.path.join(runs, f"fullres-{m}.stats.json") for m in ("report", "best")}
        t512 = None
        if all(os.path.exists(v) for v in fr.values()):
            sb, sr = load(fr["best"]), load(fr["report"])
            spp_b = sb["seconds"] / sb["spp"]
            spp_r = sr["seconds"] / sr["spp"]
            t512 = spp_best * spp_b
            lines[-1] += ";"
            lines.append(f"- measured at 512x512: Whisker best {fmt(spp_b)} s per spp, report's method in "
                         f"Whisker {fmt(spp_r)} s per spp, so "
                         f"Whisker best needs {fmt(spp_best)} x {fmt(spp_b)} = {fmt(t512)} s at 512x512, and the "
                         f"report's method in Whisker {fmt(1024 * spp_r)} s for its 1024 spp")
            cb_cpu, cr_cpu = cpu_of(fr["best"]), cpu_of(fr["report"])
            if cb_cpu and cr_cpu:
                cpu_b = cb_cpu / sb["threads"] / sb["spp"]
                cpu_r = cr_cpu / sr["threads"] / sr["spp"]
                t512_idle = spp_best * cpu_b
                lines[-1] += ";"
                lines.append(f"- on an idle machine (CPU seconds / threads, the machine being shared): "
                             f"best {fmt(cpu_b)} s per spp, report's method in Whisker {fmt(cpu_r)} s per spp, "
                             f"so {fmt(t512_idle)} s for Whisker best, {fmt(1024 * cpu_r)} s for the report's "
                             f"method's 1024 spp" + (
                                 f"; {fmt(REPORT_PROGRAM_CAT_SECONDS / t512_idle)}x less than the "
                                 f"report's program even so" if REPORT_PROGRAM_CAT_SECONDS else ""))
        worst = max(v for v in (t_best * scale, t512) if v is not None)
        lines[-1] += "."
        if REPORT_PROGRAM_CAT_SECONDS is None:
            lines.append("- no ratio to the report's program: set REPORT_PROGRAM_SECONDS to its "
                         "1024-spp time measured in the same run (bench/cat_target.sh prints it).")
        else:
            speedup = REPORT_PROGRAM_CAT_SECONDS / worst
            met = speedup >= TARGET_FACTOR
            lines.append(f"- against the report's program's {REPORT_PROGRAM_CAT_SECONDS:.0f} s "
                         f"(REPORT_PROGRAM_SECONDS, measured beside Whisker): {fmt(speedup)}x less time "
                         f"(taking the larger of the two 512x512 estimates, {fmt(worst)} s). "
                         f"Target {TARGET_FACTOR}x (<= {REPORT_PROGRAM_CAT_SECONDS / TARGET_FACTOR:.1f} s) "
                         f"by this estimate: {'reached' if met else 'not reached'}.")
        for l in lines:
            p(l)


if __name__ == "__main__":
    main()
