#!/usr/bin/python3
"""The error of each estimator as a picture and as a time-normalised power
spectrum (Celarek, Jakob, Wimmer, Lehtinen, "Quantifying the Error of Light
Transport Algorithms", EGSR 2019): where on the frequency axis an estimator
leaves its error, per unit of time.

    error_spectrum.py OUT_PREFIX LABEL:A.pfm:B.pfm:SECONDS [LABEL:...]

A and B are the same estimator's images from two seeds (linear radiance,
whisker --out-float), SECONDS the time of one. The error of one image is
e = (A - B) / sqrt(2) (independent seeds: the same variance as A's error),
taken on luminance and divided by the white of the report's display mapping
(255^2.2), as whisker-compare does. Per estimator:
  - OUT_PREFIX-noise-LABEL.png: e as a picture, mid grey = 0, +-0.1 white at
    the ends (fine grain or blotches show at a glance);
  - the radially averaged power spectrum of e (|FFT|^2 / pixels, in rings of
    one frequency step), times SECONDS: for Monte Carlo the error's power
    falls as 1/time, so this product is what an estimator costs at each
    frequency. Flat for independent pixels; a bump at low frequencies is
    error in blotches; lower is better.
Writes OUT_PREFIX-spectrum.csv and OUT_PREFIX-spectrum.png (gnuplot, log-log,
amplitude: the square root of power x time).

Needs Debian's python3-numpy and python3-pil, and gnuplot for the plot.
"""
import subprocess
import sys

import numpy as np
from PIL import Image

from pfm import read_pfm

WHITE = 255.0 ** 2.2
LUMA = np.array([0.2126, 0.7152, 0.0722])


def read_image(path):
    w, h, values = read_pfm(path, "error_spectrum")
    img = np.array(values, dtype=np.float64).reshape(h, w, 3)[::-1]  # PFM rows run bottom to top
    return img


def radial_power(e):
    """Radially averaged |FFT|^2 / N; frequencies in cycles per pixel."""
    h, w = e.shape
    power = np.abs(np.fft.fft2(e)) ** 2 / e.size
    fy = np.fft.fftfreq(h)[:, None]
    fx = np.fft.fftfreq(w)[None, :]
    ring = np.rint(np.sqrt(fx ** 2 + fy ** 2) * min(h, w)).astype(int)
    sums = np.bincount(ring.ravel(), power.ravel())
    counts = np.bincount(ring.ravel())
    keep = (counts > 0) & (np.arange(len(counts)) > 0) & (np.arange(len(counts)) <= min(h, w) // 2)
    rings = np.nonzero(keep)[0]
    return rings / min(h, w), sums[keep] / counts[keep]


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    prefix = sys.argv[1]
    curves = []
    for arg in sys.argv[2:]:
        label, a, b, secs = arg.rsplit(":", 3)
        e = ((read_image(a) - read_image(b)) / np.sqrt(2.0) / WHITE) @ LUMA
        grey = np.clip(128 + e / 0.1 * 127, 0, 255).astype(np.uint8)
        Image.fromarray(grey, mode="L").save(f"{prefix}-noise-{label}.png")
        f, p = radial_power(e)
        curves.append((label, f, p * float(secs)))
    with open(f"{prefix}-spectrum.csv", "w") as out:
        out.write("frequency," + ",".join(c[0] for c in curves) + "\n")
        for i, fr in enumerate(curves[0][1]):
            out.write(f"{fr:.6f}," + ",".join(f"{c[2][i]:.6e}" for c in curves) + "\n")
    plots = ", ".join(
        f"'{prefix}-spectrum.csv' using 1:(sqrt(${i + 2})) with lines lw 2 title '{c[0]}'"
        for i, c in enumerate(curves))
    script = f"""set terminal pngcairo size 900,560 font ',11'
set output '{prefix}-spectrum.png'
set datafile separator ','
set logscale xy
set key top right
set grid
set title 'Error amplitude spectrum x sqrt(seconds) (cat, luminance / display white; lower is better)'
set xlabel 'frequency (cycles per pixel)'
set ylabel 'sqrt(radial power x seconds)'
plot {plots}
"""
    subprocess.run(["gnuplot"], input=script.encode(), check=True)


if __name__ == "__main__":
    main()
