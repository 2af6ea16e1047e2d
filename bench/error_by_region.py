#!/usr/bin/env python3
"""Where an image's error is: by region and by colour channel.

    python3 bench/error_by_region.py A.pfm B.pfm [--json OUT.json]

A and B are two renders of one scene with different seeds (`whisker
--headless ... --seed S --out-float S.pfm`), in scene units (the default
--float-units). The MSE of one image is half the MSE between the two
(docs/PERFORMANCE.md, "How the error is measured"), in the same units as
whisker-compare: radiance / 255^2.2, averaged over the three channels.

A pixel's region is the set of channels in which its mean (A + B) / 2 is
not zero. In the report's room every wall carries a fixed set of primaries
(its albedo), so that set names the surface the camera sees there: "B" the
floor, "G" the front wall, "RGB" the white cat, and so on. A pixel that
straddles two surfaces takes the union of their channels.

Prints, per region: its share of the pixels, its share of the error, its
MSE per pixel over the image's, and which channels its error is in; then
the image's error by channel. Plain Python: no package needed.
"""
import json
import sys

from pfm import read_pfm

WHITE = 255.0 ** 2.2


def read_scaled(path):
    width, height, values = read_pfm(path, "error_by_region")
    return width, height, [v / WHITE for v in values]


def region_name(mask):
    return "".join(c for c, bit in zip("RGB", (4, 2, 1)) if mask & bit) or "none"


def analyse(a, b):
    """Per region (mask of the channels the mean image holds): pixels, squared
    errors per channel (of one image: (a - b)^2 / 2) and channel sums."""
    regions = {}
    for p in range(len(a) // 3):
        x, y = a[3 * p:3 * p + 3], b[3 * p:3 * p + 3]
        mask = sum(bit for c, bit in enumerate((4, 2, 1)) if x[c] + y[c] != 0)
        r = regions.setdefault(mask, {"pixels": 0, "se": [0.0] * 3, "sum": [0.0] * 3})
        r["pixels"] += 1
        for c in range(3):
            r["se"][c] += (x[c] - y[c]) ** 2 / 2
            r["sum"][c] += (x[c] + y[c]) / 2
    pixels = len(a) // 3
    total = sum(sum(r["se"]) for r in regions.values())
    out = {"mse": total / (3 * pixels), "regions": []}
    for mask, r in sorted(regions.items(), key=lambda kv: -sum(kv[1]["se"])):
        se = sum(r["se"])
        out["regions"].append({
            "region": region_name(mask),
            "pixel_share": r["pixels"] / pixels,
            "error_share": se / total if total > 0 else 0.0,
            "mse_per_pixel_over_image": (se / r["pixels"]) / (total / pixels) if total > 0 else 0.0,
            "channel_share": [e / se if se > 0 else 0.0 for e in r["se"]],
            "mean": [m / r["pixels"] for m in r["sum"]],
        })
    out["channel_share"] = [sum(r["se"][c] for r in regions.values()) / total if total > 0 else 0.0
                            for c in range(3)]
    return out


def main(argv):
    args = argv[1:]
    json_out = None
    if "--json" in args:
        k = args.index("--json")
        if k + 1 >= len(args):
            sys.exit("error_by_region: --json needs a file name")
        json_out = args[k + 1]
        del args[k:k + 2]
    if len(args) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    (wa, ha, a), (wb, hb, b) = read_scaled(args[0]), read_scaled(args[1])
    if (wa, ha) != (wb, hb):
        sys.exit(f"error_by_region: {args[0]} is {wa}x{ha}, {args[1]} is {wb}x{hb}")
    out = analyse(a, b)
    print(f"MSE of one image {out['mse']:.4g}")
    print("region  pixels  error  MSE/pixel  error in R, G, B   mean R, G, B")
    for r in out["regions"]:
        ch = ", ".join(f"{x:.2f}" for x in r["channel_share"])
        mn = ", ".join(f"{x:.3f}" for x in r["mean"])
        print(f"{r['region']:6s} {100 * r['pixel_share']:6.1f}% {100 * r['error_share']:5.1f}%"
              f"  {r['mse_per_pixel_over_image']:9.2f}  {ch:17s}  {mn}")
    print("error by channel R, G, B: " + ", ".join(f"{100 * x:.1f}%" for x in out["channel_share"]))
    if json_out:
        with open(json_out, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main(sys.argv)
