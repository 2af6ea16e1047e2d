#!/usr/bin/env python3
"""The denoised copy's error against a converged reference, at 1, 2, 4, 8
and 16 px, beside the raw image's and beside the denoiser's own estimate
(whisker --out-denoised's stats), bias included.

    denoise_error.py REF_A.pfm REF_B.pfm RAW.pfm DENOISED.pfm STATS.json

REF_A and REF_B: two renders of many samples with other seeds; their mean
is the reference, and a quarter of their squared difference its own noise,
subtracted from each error. Errors are mean squared errors per block and
channel after box-filtering by the scale, in the images' units; the
estimates are the stats' estimated_mse. Prints one line per scale."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pfm import read_pfm  # noqa: E402

TOOL = "denoise_error.py"


def halve(w, h, v):
    """The means of the 2 x 2 blocks of a w x h image (an odd last row or
    column dropped), and the new size."""
    bw, bh = w // 2, h // 2
    out = [0.0] * (bw * bh * 3)
    for y in range(bh):
        r0, r1, o = 3 * (2 * y) * w, 3 * (2 * y + 1) * w, 3 * y * bw
        for x in range(bw):
            for c in range(3):
                i = 6 * x + c
                out[o + 3 * x + c] = 0.25 * (v[r0 + i] + v[r0 + i + 3] + v[r1 + i] + v[r1 + i + 3])
    return bw, bh, out


def pyramid(w, h, v, scales):
    """Per scale k (powers of 2), the means of the k x k blocks per channel
    (blocks past the edge dropped): each level the 2 x 2 means of the one
    before, which are the same blocks."""
    out, k = {}, 1
    while k <= max(scales):
        if k in scales:
            out[k] = v
        w, h, v = halve(w, h, v)
        k *= 2
    return out


def main(argv):
    if len(argv) != 6:
        sys.exit(__doc__)
    imgs = [read_pfm(p, TOOL) for p in argv[1:5]]
    w, h = imgs[0][0], imgs[0][1]
    for p, (wi, hi, _) in zip(argv[2:5], imgs[1:]):
        if (wi, hi) != (w, h):
            sys.exit(f"{TOOL}: {p}: {wi}x{hi}, the reference is {w}x{h}")
    try:
        with open(argv[5]) as f:
            est = {e["scale_px"]: e for e in json.load(f)["denoised"]["estimated_mse"]}
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"{TOOL}: {argv[5]}: no denoised.estimated_mse ({e})")
    print("scale  raw MSE    denoised MSE  denoised/raw  estimated denoised/raw  estimate/true")
    scales = (1, 2, 4, 8, 16)
    levels = [pyramid(w, h, v, scales) for _, _, v in imgs]
    for k in scales:
        a, b, raw, dn = (lv[k] for lv in levels)
        n = len(a)
        ref_noise = sum((x - y) ** 2 for x, y in zip(a, b)) / (4 * n)
        ref = [(x + y) / 2 for x, y in zip(a, b)]
        err_raw = sum((x - r) ** 2 for x, r in zip(raw, ref)) / n - ref_noise
        err_dn = sum((x - r) ** 2 for x, r in zip(dn, ref)) / n - ref_noise
        e = est.get(k)
        est_ratio = e["denoised"] / e["raw"] if e and e["raw"] > 0 else float("nan")
        est_true = e["denoised"] / err_dn if e and err_dn > 0 else float("nan")
        print(f"{k:3d} px  {err_raw:10.4g} {err_dn:12.4g}  {err_dn / err_raw:12.3f}  "
              f"{est_ratio:22.3f}  {est_true:13.3f}")

if __name__ == "__main__":
    main(sys.argv)
