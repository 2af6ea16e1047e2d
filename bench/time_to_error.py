#!/usr/bin/env python3
"""Time to the report program's 1024-spp error, per estimator and scale, from
a run of bench/cat_target.sh (which calls it; the arguments are its knobs).

    time_to_error.py OUT TIMES CONFIGS SCALES REPORT_SPP REPORT_SMALL REPORT_FULL TOLERANCE

OUT holds NAME-SPP.json (whisker-compare of the two seeds' images, with
mse_by_scale); TIMES one line per process: "name spp seed seconds". The MSE of
one image is half the MSE between the two seeds' images, or, when the JSON
says "one_image": true (written by `time_to_error.py reference`, below, for
cat_target.sh's runs against a converged reference), its mse_by_scale as is.

Prints the table (rows: scales; columns: estimators) and the headline (the
worst scale of each estimator), and leaves OUT/check.json for the check
render (check(), below); exits 1 when the first estimator (the
defaults) reaches the target later than another estimator of CONFIGS at some
scale by more than TOLERANCE (a fraction).
Only the standard library.
"""
import glob
import json
import math
import os
import statistics
import sys
from collections import defaultdict


def pairs(out, tag):
    """whisker-compare's mse_by_scale of every pair of seeds rendered for
    TAG: OUT/TAG.json (the pair of SEEDS), then OUT/TAG-p2.json, -p3, ...
    (the pairs of CHECK_SEEDS), in that order."""
    found = [f"{out}/{tag}.json"] + sorted(glob.glob(f"{out}/{tag}-p[0-9]*.json"),
                                          key=lambda p: int(p.rsplit("-p", 1)[1][:-5]))
    loaded = [json.load(open(p)) for p in found if os.path.exists(p)]
    # A measurement against the reference holds one image's MSE: doubled
    # here, as if it were a pair's.
    return [{k: v * (2 if j.get("one_image") else 1) for k, v in j["mse_by_scale"].items()}
            for j in loaded]


def one_image_mse(out, tag):
    """The MSE of one image per scale (keyed as whisker-compare writes them):
    half the MSE between two seeds' images, the mean over TAG's pairs."""
    ms = pairs(out, tag)
    return {k: sum(m[k] for m in ms) / len(ms) / 2 for k in ms[0]}, len(ms)


def reference():
    """time_to_error.py reference OUT/TAG.json REF_PAIR.json IMAGE.json...:
    one image's MSE per scale against the mean of two reference renders,
    bias included: each IMAGE.json is whisker-compare of one seed's image
    against that mean, REF_PAIR.json of the two reference renders against
    each other. E|x - ref|^2 = MSE_x + MSE_ref for an x independent of the
    reference, and MSE_ref is a quarter of the pair's (the mean of two
    seeds), so MSE_x = the mean over the images of their MSE - REF_PAIR / 4.
    Writes OUT/TAG.json with "one_image": true."""
    dest, ref_pair = sys.argv[2], json.load(open(sys.argv[3]))["mse_by_scale"]
    imgs = [json.load(open(p))["mse_by_scale"] for p in sys.argv[4:]]
    mse = {k: sum(m[k] for m in imgs) / len(imgs) - ref_pair[k] / 4 for k in imgs[0]}
    with open(dest, "w") as f:
        json.dump({"mse_by_scale": mse, "one_image": True, "images": len(imgs),
                   "reference_mse": {k: v / 4 for k, v in ref_pair.items()}}, f)
    return 0


def main():
    out, times_path, configs, scales, report_spp, report_small, report_full, tol = sys.argv[1:9]
    scales = [int(k) for k in scales.split()]
    report_spp, report_small = int(report_spp), int(report_small)
    tol = float(tol)
    configs = [c.split("|") for c in configs.split(";") if c.strip()]

    times = defaultdict(list)  # (name, spp) -> seconds of each seed
    for line in open(times_path):
        name, spp, _seed, secs = line.split()
        times[(name, int(spp))].append(float(secs))
    mean = lambda xs: sum(xs) / len(xs)

    def mse(name, spp):
        m, _ = one_image_mse(out, f"{name}-{spp}")
        return {k: m[str(k)] for k in scales}

    # The report's program: plain Monte Carlo, MSE proportional to 1/spp.
    rep = mse("report", report_spp)
    target = {k: rep[k] * report_spp / 1024 for k in scales}
    t_spp, t_small = mean(times[("report", report_spp)]), mean(times[("report", report_small)])
    if report_full == "1" and times.get(("report", 1024)):
        report_1024, how = mean(times[("report", 1024)]), "measured at 1024 spp"
    else:
        report_1024 = t_spp + (1024 - report_spp) * (t_spp - t_small) / (report_spp - report_small)
        how = f"from its times at {report_small} spp ({t_small:.2f} s) and {report_spp} spp ({t_spp:.2f} s)"
    print(f"report's program: 1024 spp take {report_1024:.1f} s ({how}); target MSE per scale "
          f"({len(pairs(out, f'report-{report_spp}'))} pair(s) of seeds): "
          + ", ".join(f"{k} px {target[k]:.3e}" for k in scales))
    print()

    results = {}  # name -> {k: (spp, seconds, ratio)}
    lines = {}  # name -> (a, b): seconds = a + b spp
    for name, _flags, counts in configs:
        counts = sorted(int(s) for s in counts.split())
        pts = [(s, mse(name, s), mean(times[(name, s)])) for s in counts]
        # Time against spp: the least-squares line (a start-up cost plus a
        # cost per sample); one count: proportional.
        if len(pts) > 1:
            xs, ys = [p[0] for p in pts], [p[2] for p in pts]
            mx, my = mean(xs), mean(ys)
            b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
            a = my - b * mx
        else:
            a, b = 0.0, pts[0][2] / pts[0][0]
        row = {}
        for k in scales:
            # log-log between the two counts nearest the target (or the
            # ends), slope kept within [-2, -0.5].
            if len(pts) > 1:
                lo, hi = pts[0], pts[-1]
                for p, q in zip(pts, pts[1:]):
                    if q[1][k] <= target[k] <= p[1][k]:
                        lo, hi = p, q
                slope = math.log(hi[1][k] / lo[1][k]) / math.log(hi[0] / lo[0])
                slope = min(-0.5, max(-2.0, slope))
            else:
                lo = hi = pts[0]
                slope = -1.0
            # anchored at the count whose MSE is nearest the target
            ref = min((lo, hi), key=lambda p: abs(math.log(p[1][k] / target[k])))
            need = ref[0] * (target[k] / ref[1][k]) ** (1.0 / slope)
            secs = a + b * need
            row[k] = (need, secs, report_1024 / secs)
        results[name] = row
        lines[name] = (a, b)

    names = [c[0] for c in configs]
    print("| box filter | " + " | ".join(f"{n} ({c[1] or 'the scene' + chr(39) + 's settings'})" for n, c in zip(names, configs)) + " |")
    print("|---|" + "---|" * len(names))
    for k in scales:
        cells = []
        for n in names:
            need, secs, ratio = results[n][k]
            cells.append(f"{need:.0f} spp, {secs:.2f} s, {ratio:.1f}x")
        print(f"| {k} px | " + " | ".join(cells) + " |")
    print()
    worst = {}
    for n in names:
        k = min(scales, key=lambda s: results[n][s][2])
        worst[n] = (k, results[n][k])
        need, secs, ratio = results[n][k]
        print(f"worst scale of {n}: {k} px, {need:.0f} spp in {secs:.2f} s -> {ratio:.1f}x less than "
              f"the report program ({report_1024:.0f} s)")
    print(f"headline (the defaults at their worst scale): {worst[names[0]][1][2]:.1f}x")
    # For the check render (cat_target.sh): the samples the defaults need at
    # their worst scale, the targets and the report program's time.
    with open(f"{out}/check.json", "w") as f:
        json.dump({"name": names[0], "need": max(results[names[0]][k][0] for k in scales),
                   "target": {str(k): target[k] for k in scales}, "report_1024": report_1024,
                   "line": lines[names[0]]}, f)

    # The denoised copies (flags with --denoiser): their MSE over the raw
    # defaults' at equal samples, per scale, and their worst scale against
    # the goal. A filter narrower than a scale cannot lower the error there.
    raw0 = configs[0]
    dn = [c for c in configs[1:] if "--denoiser" in c[1]]
    for name, _flags, counts in dn:
        shared = sorted(set(int(s) for s in counts.split()) & set(int(s) for s in raw0[2].split()))
        for spp in shared:
            a, b = mse(name, spp), mse(raw0[0], spp)
            print(f"{name} at {spp} spp, MSE over {raw0[0]}'s: "
                  + ", ".join(f"{k} px {a[k] / b[k]:.3f}" for k in scales))
    if dn:
        best = max((c[0] for c in dn), key=lambda n: worst[n][1][2])
        k, (need, secs, ratio) = worst[best]
        print(f"headline (denoised, {best}, its worst scale {k} px): {ratio:.1f}x "
              f"({'meets' if ratio >= 200 else 'misses'} the 200x goal; raw {worst[names[0]][1][2]:.1f}x)")

    status = 0
    for other in [c[0] for c in configs[1:] if "--denoiser" not in c[1]]:
        lost = [k for k in scales if results[names[0]][k][1] > results[other][k][1] * (1 + tol)]
        if lost:
            print(f"FAIL: the defaults reach the target later than {other} at {', '.join(f'{k} px' for k in lost)}")
            status = 1
    if status == 0 and any("--denoiser" not in c[1] for c in configs[1:]):
        print("the defaults reach the target no later than every other estimator at every scale")
    return status


def check():
    """time_to_error.py check OUT SPP SECONDS: whether the defaults' render at
    SPP (OUT/check-SPP.json, the two seeds compared, and OUT/check-SPP-p2.json,
    ... for further pairs of seeds when present: the MSE is their mean;
    SECONDS its time) reaches the target at every scale. Prints the verdict; exits 0 when it
    does, else prints the next count to try on its last line and exits 3.
    The headline's time for SPP is read off the line through the defaults'
    timings, which ran interleaved with the report program's; the check
    renders run after them, at other moments of a shared machine."""
    out, spp, secs = sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    c = json.load(open(f"{out}/check.json"))
    m, n_pairs = one_image_mse(out, f"check-{spp}")
    over = {k: m[k] / t for k, t in c["target"].items()}
    k = max(over, key=over.get)
    print(f"check render: the defaults at {spp} spp ({secs:.2f} s; {n_pairs} pair(s) of seeds): MSE over the target "
          + ", ".join(f"{s} px {r:.3f}" for s, r in over.items()))
    if over[k] <= 1.0:
        a, b = c["line"]
        t = a + b * spp
        print(f"headline (checked render): {spp} spp in {t:.2f} s reach the target at every scale -> "
              f"{c['report_1024'] / t:.1f}x less than the report program ({c['report_1024']:.0f} s); "
              f"the time from the line through the interleaved timings")
        return 0
    # MSE falls about as 1/spp^1.2 here; at least one more sample.
    print(max(spp + 1, math.ceil(spp * over[k] ** (1 / 1.2))))
    return 3


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    sys.exit(check() if mode == "check" else reference() if mode == "reference" else main())
