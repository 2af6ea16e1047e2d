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

    python3 bench/error_by_region.py --places CAT_REF.pfm REF_A.pfm REF_B.pfm IMAGE.pfm...
        [--json OUT.json] [--masks OUT.png]

The cat's hard places instead (bench/denoise_error.sh PLACES=1): each
IMAGE's MSE against the mean of REF_A and REF_B (two converged renders of
its scene, other seeds), a quarter of their own squared difference
subtracted (so bias is included), over the whole image and over places
found in CAT_REF, a converged render of the cat scene with a seed of its
own (a place picked by the reference's own noise would be biased toward it;
the glass cat shares its camera and mesh):
  cat         the pixels holding all three primaries, each at least 0.05
              display white (the white cat; the walls hold fewer), in the
              box x 64-447, y 96-359 (the room's corners hold three too)
  silhouette  the cat's pixels with a 4-neighbour outside it, and those
              outside with one inside (2 px wide)
  whiskers    the cat's thin pixels (gone after a 3 x 3 opening) right of
              x = 370 and above y = 240, counted from the top left at
              512 x 512: the whiskers, 1-2 px wide, and the head's rim
  shadow      the floor (blue only) within 24 px below and 12 px beside
              the cat's feet (its pixels below y = 290) whose blue is
              under 80 % of the floor's median on its row: the contact
              shadow
  hot spot    the brightest 1 % of the cat scene's pixels by their sum
              (where the light falls on the cat's haunch and tail)
  glass cat   the cat's pixels (reported so for a glass-cat image)
and, in the whiskers, the share of the whiskers' red kept (their mean red
over the reference's, less the wall's, which holds none: 1 is a whisker as
bright as converged, 0 a whisker smoothed away). --masks writes the places
as a colour PNG over the reference's grey.
"""
import json
import sys

from pfm import read_pfm, write_png

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


def grid(width, height, values):
    """Pixel rows top to bottom (the PFM's are bottom to top), each a list of
    (r, g, b) tuples."""
    rows = [[tuple(values[3 * (y * width + x) + c] for c in range(3)) for x in range(width)]
            for y in range(height)]
    return rows[::-1]


def erode(mask, w, h):
    return [[mask[y][x] and all(mask[y + dy][x + dx] if 0 <= y + dy < h and 0 <= x + dx < w else False
                                for dy in (-1, 0, 1) for dx in (-1, 0, 1))
             for x in range(w)] for y in range(h)]


def dilate(mask, w, h):
    return [[any(mask[y + dy][x + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)
                 if 0 <= y + dy < h and 0 <= x + dx < w)
             for x in range(w)] for y in range(h)]


def places(ref, w, h):
    """The named masks of the module's doc, from the cat scene's reference
    rows (top to bottom)."""
    # Inside the box the cat stands in (the room's corners also hold three
    # primaries, two walls' and the ceiling's or floor's).
    box = lambda x, y: 64 * w // 512 <= x < 448 * w // 512 and 96 * h // 512 <= y < 360 * h // 512
    # At least 0.05 display white in every channel: a pixel the whisker barely
    # touches is left out (whether CAT_REF caught it is chance).
    cat = [[box(x, y) and all(v > 0.05 for v in ref[y][x]) for x in range(w)] for y in range(h)]
    n4 = lambda m, y, x: [m[j][i] for j, i in ((y - 1, x), (y + 1, x), (y, x - 1), (y, x + 1))
                          if 0 <= j < h and 0 <= i < w]
    silhouette = [[any(v != cat[y][x] for v in n4(cat, y, x)) for x in range(w)] for y in range(h)]
    opened = dilate(erode(cat, w, h), w, h)
    sx, sy = 370 * w // 512, 240 * h // 512
    whiskers = [[cat[y][x] and not opened[y][x] and x >= sx and y <= sy for x in range(w)] for y in range(h)]
    floor = [[ref[y][x][2] > 0 and ref[y][x][0] == 0 and ref[y][x][1] == 0 for x in range(w)] for y in range(h)]
    # Near the cat's feet: within 24 px below and 12 px to either side of a
    # cat pixel of a row below y = 290.
    near = [[False] * w for _ in range(h)]
    for y in range(290 * h // 512, h):
        for x in range(w):
            if cat[y][x]:
                for j in range(y + 1, min(h, y + 25)):
                    near[j][max(0, x - 12):x + 13] = [True] * (min(w, x + 13) - max(0, x - 12))
    shadow = [[False] * w for _ in range(h)]
    for y in range(h):
        fl = sorted(ref[y][x][2] for x in range(w) if floor[y][x])
        if not fl:
            continue
        median = fl[len(fl) // 2]
        for x in range(w):
            shadow[y][x] = floor[y][x] and near[y][x] and ref[y][x][2] < 0.8 * median
    sums = sorted(sum(ref[y][x]) for y in range(h) for x in range(w))
    hot_at = sums[int(0.99 * len(sums))]
    hot = [[sum(ref[y][x]) >= hot_at for x in range(w)] for y in range(h)]
    return {"silhouette": silhouette, "whiskers": whiskers, "shadow": shadow, "hot spot": hot, "cat": cat}


def take_option(args, name):
    """Removes `name FILE` from args and returns FILE (None if not given)."""
    if name not in args:
        return None
    k = args.index(name)
    if k + 1 >= len(args):
        sys.exit(f"error_by_region: {name} needs a file name")
    value = args[k + 1]
    del args[k:k + 2]
    return value


def hard_places(args, json_out):
    masks_png = take_option(args, "--masks")
    if len(args) < 4:
        sys.exit(next(u for u in __doc__.split("\n\n") if "--places" in u))
    loaded = [(p, read_scaled(p)) for p in args]
    w, h = loaded[0][1][0], loaded[0][1][1]
    for p, (wi, hi, _) in loaded[1:]:
        if (wi, hi) != (w, h):
            sys.exit(f"error_by_region: {p} is {wi}x{hi}, {args[0]} is {w}x{h}")
    cat_ref, ref_a, ref_b = (grid(*img) for _, img in loaded[:3])
    masks = places(cat_ref, w, h)
    glass = "glass" in args[1]
    names = ["image"] + [("glass cat" if glass and n == "cat" else n) for n in masks]
    mask_list = [None] + list(masks.values())
    out = {"places": {n: sum(map(sum, m)) if m else w * h for n, m in zip(names, mask_list)}, "images": []}
    print("pixels: " + ", ".join(f"{n} {c}" for n, c in out["places"].items()))
    print("image | " + " | ".join(names) + " | whiskers' red kept")
    ref = [[tuple((x + y) / 2 for x, y in zip(pa, pb)) for pa, pb in zip(ra, rb)] for ra, rb in zip(ref_a, ref_b)]
    for path, img in loaded[3:]:
        im = grid(*img)
        row = {"image": path, "mse": {}}
        for n, m in zip(names, mask_list):
            se = noise = 0.0
            count = 0
            for y in range(h):
                for x in range(w):
                    if m is None or m[y][x]:
                        count += 1
                        se += sum((a - r) ** 2 for a, r in zip(im[y][x], ref[y][x]))
                        noise += sum((a - b) ** 2 for a, b in zip(ref_a[y][x], ref_b[y][x])) / 4
            row["mse"][n] = (se - noise) / (3 * count) if count else float("nan")
        wm = masks["whiskers"]
        red_ref = sum(ref[y][x][0] for y in range(h) for x in range(w) if wm[y][x])
        red_img = sum(im[y][x][0] for y in range(h) for x in range(w) if wm[y][x])
        row["whiskers_red_kept"] = red_img / red_ref if red_ref > 0 else float("nan")
        out["images"].append(row)
        print(f"{path} | " + " | ".join(f"{row['mse'][n]:.3e}" for n in names)
              + f" | {row['whiskers_red_kept']:.3f}")
    if json_out:
        with open(json_out, "w") as f:
            json.dump(out, f, indent=1)
    if masks_png:
        colours = {"silhouette": (255, 255, 0), "whiskers": (255, 0, 0), "shadow": (0, 255, 255),
                   "hot spot": (255, 0, 255)}
        rows = []
        for y in range(h):
            row = []
            for x in range(w):
                g = int(255 * min(1.0, (sum(cat_ref[y][x]) / 3) ** (1 / 2.2)))
                px = (g // 2, g // 2, g // 2)
                for n, c in colours.items():
                    if masks[n][y][x]:
                        px = c
                row.append(px)
            rows.append(row)
        write_png(masks_png, rows)


def main(argv):
    args = argv[1:]
    json_out = take_option(args, "--json")
    if args and args[0] == "--places":
        return hard_places(args[1:], json_out)
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
