#!/usr/bin/env python3
"""The closed-form scene of the speed-against-error report: a point light
inside a closed diffuse sphere (the core test IndirectLight.OffCentreLightIn
ClosedSphere), seen from inside, no anti-aliasing. Every pixel is known:

    L(y) = rho/pi [I cos / |c - y|^2 + (I / R^2) rho (1 - rho^(B-1)) / (1 - rho)] / (4 pi)

with y the camera ray's hit, cos the cosine at y towards the light c, and
B = max_depth + 1 diffuse hits (a cosine-sampled direction inside a sphere
lands uniformly on its area, so every indirect bounce sees the mean
irradiance). The reference image has no noise at all.

    closed_sphere.py SCENE.json EXACT.pfm RES
"""
import json
import math
import struct
import sys

R, RHO, I = 10.0, 0.5, 1.0e9
LIGHT = (3.0, -2.0, 1.0)
EYE = (0.0, 0.0, 5.0)
FOV = 90.0
DEPTH = 5


def main():
    scene_path, pfm_path, res = sys.argv[1], sys.argv[2], int(sys.argv[3])
    scene = {
        "name": "closed-sphere",
        "description": "Closed-form check: point light inside a closed grey diffuse sphere, "
                       "camera inside (bench/convergence/closed_sphere.py).",
        "camera": {"position": list(EYE), "look_at": [0, 0, -10], "up": [0, 1, 0],
                   "fov": FOV, "width": res, "height": res},
        "light": {"position": list(LIGHT), "intensity": I},
        "settings": {"spp": 1, "max_depth": DEPTH, "indirect": True, "fresnel": False,
                     "aa": False, "seed": 0, "target_spp": 1},
        "spheres": [{"name": "shell", "center": [0, 0, 0], "radius": R,
                     "material": {"type": "diffuse", "albedo": [RHO, RHO, RHO]}}],
    }
    with open(scene_path, "w") as f:
        json.dump(scene, f, indent=2)

    # Camera looks down -z with +y up (docs/SCENES.md conventions), so the camera
    # frame is the world frame: direction (j - W/2 + 0.5, H/2 - i - 0.5, -focal).
    focal = res / (2.0 * math.tan(math.radians(FOV) / 2.0))
    B = DEPTH + 1
    indirect = I / (R * R) * RHO * (1 - RHO ** (B - 1)) / (1 - RHO)
    rows = []
    for i in range(res):
        row = []
        for j in range(res):
            d = (j - res / 2 + 0.5, res / 2 - i - 0.5, -focal)
            n = math.sqrt(sum(v * v for v in d))
            d = tuple(v / n for v in d)
            b = sum(o * v for o, v in zip(EYE, d))
            oo = sum(o * o for o in EYE)
            t = -b + math.sqrt(b * b - (oo - R * R))
            y = tuple(o + t * v for o, v in zip(EYE, d))
            nrm = tuple(-v / R for v in y)  # inward
            to = tuple(c - v for c, v in zip(LIGHT, y))
            d2 = sum(v * v for v in to)
            cos = sum(a * b for a, b in zip(nrm, to)) / math.sqrt(d2)
            L = RHO / math.pi * (I * cos / d2 + indirect) / (4 * math.pi)
            row.append(L)
        rows.append(row)
    with open(pfm_path, "wb") as f:
        f.write(f"PF\n{res} {res}\n-1.0\n".encode())
        for row in reversed(rows):  # PFM stores the bottom row first
            for L in row:
                f.write(struct.pack("<fff", L, L, L))


if __name__ == "__main__":
    main()
