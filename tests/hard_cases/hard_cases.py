#!/usr/bin/env python3
"""Hard cases for Whisker's numerics, run on the real program (headless).

Each case builds scene files, renders them with `whisker --headless`, and
checks the image against one of:
  - an invariance: the same scene moved (to 1e6) or scaled (1e-5 to 1e4, the
    light's intensity by the square), or scaled down and moved far, must
    render the same image;
  - a closed form: a closed room with the light outside is black;
  - a double-precision reference: a small direct-light tracer below, for
    diffuse spheres and planes lit by the point light (report section 1:
    L = albedo / pi * I / (4 pi d^2) * max(0, n.l), or 0 in shadow).

    hard_cases.py --whisker build/whisker [--case NAME ...] [--keep DIR]

Exit 0 when every case holds; otherwise one line per failed check and exit 1.
Small images (64x64 unless a case needs more) keep the run short.
"""
import argparse
import copy
import json
import math
import os
import pathlib
import struct
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "assets" / "scenes"
CAT_OBJ = ROOT / "assets" / "cat.obj"


# --------------------------------------------------------------------------
# Rendering and images

class Runner:
    def __init__(self, whisker, workdir):
        self.whisker = whisker
        self.dir = pathlib.Path(workdir)
        self.n = 0

    def render(self, scene, *args, frames=1, spp=1):
        """Renders a scene dict; returns (image, stats)."""
        self.n += 1
        tag = f"{self.n:03d}-{scene.get('name', 'scene')}"
        sp = self.dir / f"{tag}.json"
        sp.write_text(json.dumps(scene, indent=1))
        out, st = self.dir / f"{tag}.pfm", self.dir / f"{tag}-stats.json"
        cmd = [self.whisker, "--headless", "--scene", str(sp), "--frames", str(frames),
               "--spp", str(spp), "--threads", "2", "--quiet",
               "--out-float", str(out), "--stats", str(st), *args]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} exited {r.returncode}: {r.stderr.strip()}")
        return read_pfm(out), json.loads(st.read_text())


def read_pfm(path):
    data = pathlib.Path(path).read_bytes()
    parts, pos = [], 0
    while len(parts) < 4:  # "PF", width, height, scale
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        parts.append(data[pos:end].decode())
        pos = end
    pos += 1
    w, h, scale = int(parts[1]), int(parts[2]), float(parts[3])
    fmt = ("<" if scale < 0 else ">") + f"{w * h * 3}f"
    vals = struct.unpack_from(fmt, data, pos)
    # PFM rows run bottom to top; return rows top to bottom as [r, g, b] lists.
    rows = [[list(vals[(y * w + x) * 3:(y * w + x) * 3 + 3]) for x in range(w)]
            for y in range(h)]
    return {"w": w, "h": h, "px": rows[::-1]}


def display(v):
    """The report's display mapping, min(255, L^(1/2.2)), as a float."""
    return min(255.0, max(0.0, v) ** (1.0 / 2.2)) if math.isfinite(v) else float("nan")


def differing_pixels(a, b, levels=2.0, scale_b=1.0):
    """Pixels where a channel differs by more than `levels` display levels."""
    n = 0
    for ra, rb in zip(a["px"], b["px"]):
        for pa, pb in zip(ra, rb):
            if any(not abs(display(x) - display(y * scale_b)) <= levels for x, y in zip(pa, pb)):
                n += 1
    return n


def image_mean(img):
    s = sum(sum(p) for row in img["px"] for p in row)
    return s / (img["w"] * img["h"] * 3)


def load_scene(name, size=64):
    s = json.loads((SCENES / f"{name}.json").read_text())
    s["camera"]["width"] = s["camera"]["height"] = size
    for m in s.get("meshes", []):
        m["path"] = str(CAT_OBJ) if m["path"] == "cat.obj" else m["path"]
    return s


def translated(scene, t):
    s = copy.deepcopy(scene)
    add = lambda v: [v[0] + t[0], v[1] + t[1], v[2] + t[2]]
    s["camera"]["position"] = add(s["camera"]["position"])
    s["camera"]["look_at"] = add(s["camera"]["look_at"])
    s["light"]["position"] = add(s["light"]["position"])
    for sp in s.get("spheres", []):
        sp["center"] = add(sp["center"])
    for m in s.get("meshes", []):
        m["translate"] = add(m.get("translate", [0, 0, 0]))
    return s


def scaled(scene, k):
    """Every length times k about the origin; the intensity times k^2, so the
    radiance (I / d^2) is unchanged."""
    s = copy.deepcopy(scene)
    mul = lambda v: [x * k for x in v]
    s["camera"]["position"] = mul(s["camera"]["position"])
    s["camera"]["look_at"] = mul(s["camera"]["look_at"])
    s["light"]["position"] = mul(s["light"]["position"])
    s["light"]["intensity"] = s["light"]["intensity"] * k * k
    for sp in s.get("spheres", []):
        sp["center"] = mul(sp["center"])
        sp["radius"] *= k
        if "inner_radius" in sp:
            sp["inner_radius"] *= k
    for m in s.get("meshes", []):
        m["scale"] = m.get("scale", 1.0) * k
        m["translate"] = mul(m.get("translate", [0, 0, 0]))
    return s


def diffuse(name, center, radius, albedo):
    return {"name": name, "center": center, "radius": radius,
            "material": {"type": "diffuse", "albedo": albedo}}


def room():
    """The report's six wall spheres."""
    return [s for s in load_scene("three-balls")["spheres"]
            if s["material"]["type"] == "diffuse"]


def scene_of(name, spheres, camera, light, meshes=(), **settings):
    base = {"spp": 1, "max_depth": 5, "indirect": False, "fresnel": False, "aa": False,
            "seed": 0, "target_spp": 1}
    base.update(settings)
    s = {"name": name, "camera": camera, "light": light, "settings": base,
         "spheres": spheres}
    if meshes:
        s["meshes"] = list(meshes)
    return s


def camera(position, look_at, fov, size=64, up=(0, 1, 0)):
    return {"position": list(position), "look_at": list(look_at), "up": list(up),
            "fov": fov, "width": size, "height": size}


# --------------------------------------------------------------------------
# A double-precision reference for direct light on diffuse spheres and planes

def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def mul(a, k): return (a[0] * k, a[1] * k, a[2] * k)
def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def norm(a): return mul(a, 1.0 / math.sqrt(dot(a, a)))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def sphere_roots(o, d, c, r):
    """Both roots of |o + t d - c| = r for unit d, or None (stable form)."""
    oc = sub(o, c)
    b = dot(oc, d)
    q = dot(oc, oc) - r * r
    disc = b * b - q
    if disc < 0:
        return None
    s = math.sqrt(disc)
    t1 = -b - s if b > 0 else q / (-b + s) if (-b + s) != 0 else -b
    t2 = q / t1 if t1 != 0 else -b + s
    return (min(t1, t2), max(t1, t2))


class Reference:
    """Spheres: (center, radius, albedo). Planes: (point, unit normal, albedo,
    half-size) squares facing +normal. Pixel values in the PFM's units.
    shadow_only: spheres (center, radius) that camera rays pass straight
    through but that block shadow rays: glass of index 1 without Fresnel,
    which in the report's model bends nothing and casts a full shadow."""

    def __init__(self, spheres, planes, light, intensity, shadow_only=()):
        self.spheres, self.planes = spheres, planes
        self.light, self.intensity = light, intensity
        self.shadow_only = list(shadow_only)

    def hit(self, o, d):
        """(t, normal, albedo, tie): tie when another surface is met within
        1e-6 of t (a ray through the seam of two walls: which one it meets
        is decided by the float rounding of the camera's direction)."""
        hits = []
        for c, r, alb in self.spheres:
            roots = sphere_roots(o, d, c, r)
            if roots:
                for t in roots:
                    if 1e-12 < t:
                        p = add(o, mul(d, t))
                        hits.append((t, norm(sub(p, c)), alb))
                        break
        for p0, n, alb, half in self.planes:
            den = dot(d, n)
            if den != 0:
                t = dot(sub(p0, o), n) / den
                p = add(o, mul(d, t))
                q = sub(p, p0)
                if 1e-12 < t and max(abs(x) for x in q) <= half:
                    hits.append((t, n, alb))
        if not hits:
            return (math.inf, None, None, False)
        hits.sort(key=lambda h: h[0])
        tie = len(hits) > 1 and hits[1][0] - hits[0][0] <= 1e-6 * hits[0][0]
        return hits[0] + (tie,)

    def shade(self, o, d):
        """(rgb, ambiguous): ambiguous when the shadow test is within a hair of
        its decision (a tangent shadow ray or a point on a shadow edge)."""
        t, n, alb, tie = self.hit(o, d)
        if n is None:
            return (0.0, 0.0, 0.0), False
        if tie:
            return (0.0, 0.0, 0.0), True
        p = add(o, mul(d, t))
        if dot(n, d) > 0:
            n = mul(n, -1.0)
        to_l = sub(self.light, p)
        d2 = dot(to_l, to_l)
        dist = math.sqrt(d2)
        wl = mul(to_l, 1.0 / dist)
        cos = dot(n, wl)
        if cos <= 0:
            return (0.0, 0.0, 0.0), abs(cos) < 1e-6
        ambiguous = cos < 1e-6
        blockers = list(self.spheres) + [(c, r, None) for c, r in self.shadow_only]
        for c, r, _ in blockers:  # the segment p -> light against each sphere
            m = sub(self.light, c)
            if abs(math.sqrt(dot(m, m)) - r) <= 1e-12 * (r + dist):
                # The light on this sphere: the line meets it at the light
                # (t = dist) and at t = dist - 2 m.wl. The segment crosses the
                # sphere iff that root lies in (0, dist): p outside and below
                # the tangent plane at the light.
                other = dist - 2.0 * dot(m, wl)
                if abs(dot(m, wl)) <= 1e-9 * r or abs(other) <= 1e-9 * (r + dist):
                    ambiguous = True
                elif 0.0 < other < dist:
                    return (0.0, 0.0, 0.0), ambiguous
                continue
            roots = sphere_roots(p, wl, c, r)
            if roots is None:
                continue
            t1, t2 = roots
            # The segment leaves p, which may lie on this very sphere: the
            # root there (t ~ 0) is p itself, not an occluder.
            start = 1e-9 * (r + dist)
            if t2 <= start:
                continue
            lo, hi = max(t1, start), min(t2, dist)
            margin = 1e-7 * (r + dist)
            if hi - lo > margin:
                return (0.0, 0.0, 0.0), ambiguous
            if hi - lo > -margin:
                ambiguous = True
        for p0, pn, _, half in self.planes:
            den = dot(wl, pn)
            if den != 0:
                tt = dot(sub(p0, p), pn) / den
                q = sub(add(p, mul(wl, tt)), p0)
                if 1e-9 * dist < tt < dist * (1 - 1e-9) and max(abs(x) for x in q) <= half:
                    return (0.0, 0.0, 0.0), ambiguous
        k = self.intensity * cos / (4 * math.pi * math.pi * d2)
        return tuple(a * k for a in alb), ambiguous

    def image(self, cam):
        """Pixel centres, as docs/SCENES.md's camera (no anti-aliasing). Traced
        relative to the camera (the scene moved so that the camera is at 0,
        in double): the tolerances above are relative to the distances in
        the scene, so a small scene far from the origin is traced as well as
        one at the origin."""
        pos = tuple(cam["position"])
        if any(pos):
            rel = copy.copy(self)
            rel.spheres = [(sub(c, pos), r, a) for c, r, a in self.spheres]
            rel.planes = [(sub(p0, pos), n, a, half) for p0, n, a, half in self.planes]
            rel.shadow_only = [(sub(c, pos), r) for c, r in self.shadow_only]
            rel.light = sub(self.light, pos)
            moved = dict(cam, position=[0.0, 0.0, 0.0], look_at=list(sub(tuple(cam["look_at"]), pos)))
            return rel.image(moved)
        w, h = cam["width"], cam["height"]
        fwd = norm(sub(tuple(cam["look_at"]), pos))
        right = norm(cross(fwd, tuple(cam["up"])))
        up = cross(right, fwd)
        focal = w / (2 * math.tan(math.radians(cam["fov"]) / 2))
        px, amb = [], []
        for i in range(h):
            row, arow = [], []
            for j in range(w):
                x, y = j - w / 2 + 0.5, h / 2 - i - 0.5
                d = norm(add(add(mul(right, x), mul(up, y)), mul(fwd, focal)))
                v, a = self.shade(pos, d)
                row.append(list(v)); arow.append(a)
            px.append(row); amb.append(arow)
        return {"w": w, "h": h, "px": px}, amb


def wrong_against_reference(img, ref, amb, rel=0.01, levels=1.0):
    """Pixels off the reference by more than `rel` and `levels` display levels
    in a channel, ambiguous pixels (and their 4 neighbours, for rays that are a
    float rounding away from a silhouette) left out."""
    n = 0
    h, w = img["h"], img["w"]
    for i in range(h):
        for j in range(w):
            if any(amb[y][x] for y, x in ((i, j), (i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1))
                   if 0 <= y < h and 0 <= x < w):
                continue
            for a, b in zip(img["px"][i][j], ref["px"][i][j]):
                if not (abs(a - b) <= rel * abs(b) or abs(display(a) - display(b)) <= levels):
                    n += 1
                    break
    return n


# --------------------------------------------------------------------------
# The cases. Each yields (what, ok, detail).

def case_offset(run):
    """The scene moved far from the origin renders the same image."""
    for name, flags, allowed in (("three-balls", [], 0.005),
                                 ("three-balls-fresnel", ["--fresnel", "on"], 0.005),
                                 ("cat", ["--indirect", "off", "--aa", "off"], 0.005),
                                 ("indirect", [], 0.02)):
        base = load_scene(name)
        ref, _ = run.render(base, *flags, spp=4)
        for t in (1e5, 1e6):
            img, _ = run.render(translated(base, (t, t, t)), *flags, spp=4)
            n = differing_pixels(img, ref)
            mr, mi = image_mean(ref), image_mean(img)
            ok = n <= allowed * 64 * 64 and abs(mi - mr) <= 0.002 * mr
            yield (f"{name} moved by {t:g}", ok,
                   f"{n} of 4096 pixels differ (allowed {allowed * 4096:.0f}); "
                   f"mean {mi:.6g} against {mr:.6g}")


def case_scale(run):
    """Every length times k (intensity times k^2) renders the same image."""
    for name, flags in (("three-balls", []), ("three-balls-fresnel", ["--fresnel", "on"]),
                        ("cat", ["--indirect", "off", "--aa", "off"])):
        base = load_scene(name)
        ref, _ = run.render(base, *flags, spp=4)
        for k in (1e-5, 1e-3, 1e4):
            img, _ = run.render(scaled(base, k), *flags, spp=4)
            n = differing_pixels(img, ref)
            yield (f"{name} scaled by {k:g}", n <= 20, f"{n} of 4096 pixels differ (allowed 20)")


def case_small_far(run):
    """A small scene far from the origin: scaled down, then moved by an offset
    of 1e6 to 1e7 times its size, and moved by an offset that no float holds
    (123456.789): the same image as the scene scaled alone, within the seam
    pixels that scaling itself may flip. Positions are read and kept in double
    (scene.h), render space is relative to the camera."""
    for name, flags in (("three-balls", []), ("three-balls-fresnel", ["--fresnel", "on"]),
                        ("indirect", []), ("cat", ["--indirect", "off", "--aa", "off"])):
        base = load_scene(name)
        for k, t in ((1e-3, 1e4), (1e-4, 1e3), (1, 123456.789)):
            small = scaled(base, k)
            ref, _ = run.render(small, *flags, spp=4)
            img, _ = run.render(translated(small, (t, -t, t)), *flags, spp=4)
            n = differing_pixels(img, ref)
            mr, mi = image_mean(ref), image_mean(img)
            ok = n <= 4 and abs(mi - mr) <= 1e-3 * mr
            yield (f"{name} scaled by {k:g}, moved by {t:g}", ok,
                   f"{n} of 4096 pixels differ (allowed 4); mean {mi:.6g} against {mr:.6g}")


def case_thin_shell(run):
    """A hollow glass ball whose shell thins to 1e-6 converges to the same
    image as a 1e-2 shell (a thin parallel shell displaces rays by about its
    thickness, far below a pixel here)."""
    def with_shell(thickness, centre=(0.0, 0.0, 0.0)):
        s = scene_of("thin-shell", room() + [{
            "name": "hollow", "center": list(centre), "radius": 10,
            "inner_radius": 10 - thickness, "material": {"type": "hollow_glass", "ior": 1.5}}],
            camera((0, 0, 55), (0, 0, 0), 60), {"position": [-10, 20, 40], "intensity": 2e10})
        return s
    ref, _ = run.render(with_shell(1e-2))
    for th in (1e-4, 1e-6):
        img, _ = run.render(with_shell(th))
        n = differing_pixels(img, ref)
        yield (f"hollow shell {th:g} thick", n <= 4, f"{n} pixels differ from a 1e-2 shell (allowed 4)")
    # A ball of radius 1 (where a float holds a 1e-7 shell; at radius 10 the
    # reader refuses it: 10 - 1e-7 rounds to 10), also moved by 1e6, against
    # the reference that sees through the shell and lets it block the light.
    walls = room()
    for th in (1e-5, 1e-7):
        for shift in (0.0, 1e6):
            k = 0.1
            s = scaled(scene_of("thin-shell", walls + [{
                "name": "hollow", "center": [0, 0, 0], "radius": 10,
                "inner_radius": 5, "material": {"type": "hollow_glass", "ior": 1.5}}],
                camera((0, 0, 55), (0, 0, 0), 60), {"position": [-10, 20, 40], "intensity": 2e10}), k)
            s["spheres"][-1]["radius"], s["spheres"][-1]["inner_radius"] = 1.0, 1.0 - th
            s = translated(s, (shift, shift, shift))
            img, _ = run.render(s)
            mv = lambda v: tuple(a * k + shift for a in v)
            ref, amb = Reference([(mv(w["center"]), w["radius"] * k, tuple(w["material"]["albedo"]))
                                  for w in walls], [], mv((-10, 20, 40)), 2e10 * k * k,
                                 shadow_only=[(mv((0, 0, 0)), 1.0)]).image(s["camera"])
            n = wrong_against_reference(img, ref, amb)
            at = f", moved by {shift:g}" if shift else ""
            yield (f"hollow ball r=1, shell {th:g} thick{at}", n <= 2,
                   f"{n} pixels off the see-through reference (allowed 2)")


def case_tiny_ball(run):
    """A ball of radius 1e-3 fifty units from the origin, in front of a ball of
    radius 0.015, seen from close by: shading, the terminators and the small
    ball's shadow against the double-precision reference."""
    c, back = (50.0, 0.0, 0.0), (50.0, 0.0, -0.02)
    light = (50.003, 0.003, 0.004)
    cam = camera((50.0, 0.0, 0.01), c, 40)
    s = scene_of("tiny-ball", [diffuse("tiny", list(c), 1e-3, [1, 1, 1]),
                               diffuse("back", list(back), 0.015, [1, 1, 1])], cam,
                 {"position": list(light), "intensity": 2.0})
    img, _ = run.render(s)
    ref, amb = Reference([(c, 1e-3, (1, 1, 1)), (back, 0.015, (1, 1, 1))], [], light,
                         2.0).image(cam)
    n = wrong_against_reference(img, ref, amb)
    yield ("ball r=1e-3 at x=50", n <= 2, f"{n} pixels off the double reference (allowed 2)")
    # Smaller and farther: r = 1e-5 at 1e6 and r = 1e-6 at 9.99e6 (the
    # reader's limit), the whole scene scaled with the ball, the intensity
    # with the square of the scale.
    for r, x in ((1e-5, 1e6), (1e-6, 9.99e6)):
        k = r / 1e-3
        c, back = (x, 0.0, 0.0), (x, 0.0, -20 * r)
        light = (x + 3 * r, 3 * r, 4 * r)
        cam = camera((x, 0.0, 10 * r), c, 40)
        s = scene_of("tiny-ball", [diffuse("tiny", list(c), r, [1, 1, 1]),
                                   diffuse("back", list(back), 15 * r, [1, 1, 1])], cam,
                     {"position": list(light), "intensity": 2.0 * k * k})
        img, _ = run.render(s)
        ref, amb = Reference([(c, r, (1, 1, 1)), (back, 15 * r, (1, 1, 1))], [], light,
                             2.0 * k * k).image(cam)
        n = wrong_against_reference(img, ref, amb)
        yield (f"ball r={r:g} at x={x:g}", n <= 2, f"{n} pixels off the double reference (allowed 2)")


def case_light_on_surface(run):
    """A light exactly on a surface: what it can see is lit. Also with the
    scene moved by 1e4, where a spawn offset is larger: a shadow ray must be
    aimed at the light from where it starts, or it meets the light's surface."""
    for shift in (0.0, 1e4):
        yield from light_on_surface(run, shift)


def light_on_surface(run, shift):
    at = f" (moved by {shift:g})" if shift else ""
    mv = lambda v: tuple(x + shift for x in v)
    walls = room()
    for w in walls:
        w["center"] = list(mv(w["center"]))
    ref_walls = [(tuple(w["center"]), w["radius"], tuple(w["material"]["albedo"])) for w in walls]
    cam = camera(mv((0, 0, 55)), mv((0, 0, 0)), 60)
    # On top of a ball.
    ball = diffuse("ball", list(mv((0, 0, 0))), 10, [1, 1, 1])
    light = mv((0.0, 10.0, 0.0))
    s = scene_of("light-on-ball", walls + [ball], cam, {"position": list(light), "intensity": 2e10})
    img, _ = run.render(s)
    ref, amb = Reference(ref_walls + [(mv((0, 0, 0)), 10, (1, 1, 1))], [], light, 2e10).image(cam)
    n = wrong_against_reference(img, ref, amb)
    yield ("light on top of a ball" + at, n <= 2, f"{n} pixels off the reference (allowed 2)")
    # On the walls: the back wall (the sphere centred at z = -1000, radius
    # 940), the left wall and the floor.
    for light in ((0.0, 0.0, -60.0), (-60.0, 0.0, 0.0), (0.0, -10.0, -30.0)):
        light = mv(light)
        s = scene_of("light-on-wall", walls + [ball], cam,
                     {"position": list(light), "intensity": 2e10})
        img, _ = run.render(s)
        ref, amb = Reference(ref_walls + [(mv((0, 0, 0)), 10, (1, 1, 1))], [], light,
                             2e10).image(cam)
        n = wrong_against_reference(img, ref, amb)
        yield (f"light on a wall at {light}" + at, n <= 2, f"{n} pixels off the reference (allowed 2)")
    # On a flat mesh: a square floor at y = -5, a ball above it.
    obj = run.dir / "floor.obj"
    obj.write_text("v -50 -5 -50\nv 50 -5 -50\nv 50 -5 50\nv -50 -5 50\nf 1 3 2\nf 1 4 3\n")
    light = mv((0.0, -5.0, 0.0))
    ball = diffuse("ball", list(mv((0, 5, 0))), 5, [1, 1, 1])
    mesh = {"name": "floor", "path": str(obj), "translate": list(mv((0, 0, 0))),
            "material": {"type": "diffuse", "albedo": [1, 1, 1]}}
    s = scene_of("light-on-mesh", walls + [ball], cam, {"position": list(light), "intensity": 2e10},
                 meshes=[mesh])
    img, _ = run.render(s)
    ref, amb = Reference(ref_walls + [(mv((0, 5, 0)), 5, (1, 1, 1))],
                         [(mv((0, -5, 0)), (0, 1, 0), (1, 1, 1), 50)], light, 2e10).image(cam)
    n = wrong_against_reference(img, ref, amb)
    yield ("light on a flat mesh" + at, n <= 2, f"{n} pixels off the reference (allowed 2)")


def on_sphere(center, radius, direction):
    """The point of a sphere in a direction from its centre, in double."""
    u = norm(direction)
    return add(tuple(center), mul(u, radius))


def cat_triangle(scene):
    """The largest cat triangle facing the camera, its corners in double (the
    OBJ's scale and translation applied), and its face number in the OBJ."""
    m = scene["meshes"][0]
    vs, best, face = [], None, 0
    cam = tuple(scene["camera"]["position"])
    for line in CAT_OBJ.read_text().splitlines():
        f = line.split()
        if f and f[0] == "v":
            vs.append(add(mul(tuple(float(x) for x in f[1:4]), m["scale"]), tuple(m["translate"])))
        elif f and f[0] == "f":
            face += 1
            a, b, c = (vs[int(x.split("/")[0]) - 1] for x in f[1:4])
            n = cross(sub(b, a), sub(c, a))
            area2 = math.sqrt(dot(n, n))
            ctr = mul(add(add(a, b), c), 1.0 / 3.0)
            if area2 > 0 and dot(n, sub(cam, ctr)) > 0 and (best is None or area2 > best[0]):
                best = (area2, (a, b, c), face)
    return best[1], best[2]


def case_light_exactly_on_surface(run):
    """A light exactly on a wall of the report's room (the ceiling, the wall
    behind the camera, the front wall, off their axes too), on a small
    diffuse ball and on glass, each scaled by 1e-3, 1 and 1e4, against the
    double reference: what lies in front of the surface is lit, also at
    grazing angles just past the wall's edge, where the float root of the
    wall at the light itself fell before the shadow ray's end. Then a light
    on a cat triangle: the same image at every scale."""
    base = load_scene("indirect")
    walls = [w for w in base["spheres"] if w["material"]["type"] == "diffuse"]
    ceiling, front, behind = ((0, 1000, 0), 940), ((0, 0, -1000), 940), ((0, 0, 1000), 940)
    ball_c, ball_r = (7.0, -13.0, 4.0), 1.5
    glass = {"name": "glass", "center": [0, 0, 0], "radius": 10,
             "material": {"type": "glass", "ior": 1.0}}
    lights = [("on the ceiling", on_sphere(*ceiling, (0, -1, 0)), False),
              ("on the ceiling off its axis", on_sphere(*ceiling, (0.021, -1, -0.013)), False),
              ("on the wall behind", on_sphere(*behind, (0, 0, -1)), False),
              ("on the wall behind off its axis", on_sphere(*behind, (-0.03, 0.017, -1)), False),
              ("on the front wall off its axis", on_sphere(*front, (0.025, 0.04, 1)), False),
              ("on a small ball", on_sphere(ball_c, ball_r, (-0.3, 0.8, 0.5)), False),
              ("on a glass ball", on_sphere((0, 0, 0), 10, (0.2, 1, 0.4)), True)]
    for what, light, with_glass in lights:
        for k in (1e-3, 1.0, 1e4):
            spheres = walls + [diffuse("ball", list(ball_c), ball_r, [1, 1, 1])]
            if with_glass:
                spheres = spheres + [glass]
            s = scaled(scene_of("light-exactly-on-surface", spheres, camera((0, 0, 55), (0, 0, 0), 60),
                                {"position": list(light), "intensity": 2e10}), k)
            img, _ = run.render(s)
            ref, amb = Reference([(tuple(w["center"]), w["radius"], tuple(w["material"]["albedo"]))
                                  for w in s["spheres"] if w["material"]["type"] == "diffuse"],
                                 [], tuple(s["light"]["position"]), s["light"]["intensity"],
                                 shadow_only=[(tuple(g["center"]), g["radius"]) for g in s["spheres"]
                                              if g["material"]["type"] == "glass"]).image(s["camera"])
            n = wrong_against_reference(img, ref, amb)
            yield (f"light {what}, scaled by {k:g}", n <= 2, f"{n} pixels off the reference (allowed 2)")
    # On a cat triangle: against the same cat without that triangle (a
    # segment meets the triangle's plane only at the light, so the triangle
    # shadows nothing; points behind it are shadowed by the rest of the
    # closed cat), leaving out the pixels that see the triangle or the hole.
    for k in (1e-3, 1.0, 1e4):
        cat = scaled(load_scene("cat"), k)
        cat["settings"].update({"indirect": False, "aa": False})
        tri, index = cat_triangle(cat)
        cat["light"]["position"] = list(mul(add(add(tri[0], tri[1]), tri[2]), 1.0 / 3.0))
        img, _ = run.render(cat)
        holed = run.dir / "cat-holed.obj"
        lines, face = [], 0
        for line in CAT_OBJ.read_text().splitlines():
            if line.split()[:1] == ["f"]:
                face += 1
                if face == index:
                    continue
            lines.append(line)
        holed.write_text("\n".join(lines) + "\n")
        cat["meshes"][0]["path"] = str(holed)
        ref, _ = run.render(cat)
        seen = pixels_seeing(cat["camera"], tri)
        n = 0
        for i in range(img["h"]):
            for j in range(img["w"]):
                near = any((y, x) in seen for y in (i - 1, i, i + 1) for x in (j - 1, j, j + 1))
                if not near and any(abs(display(a) - display(b)) > 2.0
                                    for a, b in zip(img["px"][i][j], ref["px"][i][j])):
                    n += 1
        yield (f"light on a cat triangle, scaled by {k:g}", n <= 2,
               f"{n} pixels differ from the cat without the triangle (allowed 2)")


def pixels_seeing(cam, tri):
    """The pixels (row, column) whose centre ray meets the triangle (in double)."""
    pos = tuple(cam["position"])
    w, h = cam["width"], cam["height"]
    fwd = norm(sub(tuple(cam["look_at"]), pos))
    right = norm(cross(fwd, tuple(cam["up"])))
    up = cross(right, fwd)
    focal = w / (2 * math.tan(math.radians(cam["fov"]) / 2))
    a, b, c = (sub(v, pos) for v in tri)
    n = cross(sub(b, a), sub(c, a))
    seen = set()
    for i in range(h):
        for j in range(w):
            x, y = j - w / 2 + 0.5, h / 2 - i - 0.5
            d = add(add(mul(right, x), mul(up, y)), mul(fwd, focal))
            den = dot(d, n)
            if den == 0:
                continue
            p = mul(d, dot(a, n) / den)
            if all(dot(cross(sub(q1, q0), sub(p, q0)), n) >= 0 for q0, q1 in ((a, b), (b, c), (c, a))):
                seen.add((i, j))
    return seen


def case_far_obj(run):
    """OBJ coordinates near 1e6, brought back by the scene's scale and
    translate, give the cat where the original file puts it."""
    far = run.dir / "cat-far.obj"
    with open(CAT_OBJ) as src, open(far, "w") as dst:
        for line in src:
            if line.startswith("v "):
                x, y, z = (float(v) for v in line.split()[1:4])
                dst.write(f"v {x + 1e6!r} {y + 1e6!r} {z + 1e6!r}\n")
            elif line.startswith("mtllib") or line.startswith("usemtl"):
                continue
            else:
                dst.write(line)
    base = load_scene("cat", 128)
    flags = ["--indirect", "off", "--aa", "off"]
    ref, _ = run.render(base, *flags)
    s = copy.deepcopy(base)
    m = s["meshes"][0]
    m["path"] = str(far)
    m["translate"] = [t - m["scale"] * 1e6 for t in m["translate"]]
    img, _ = run.render(s, *flags)
    n = differing_pixels(img, ref)
    yield ("cat OBJ at 1e6, moved back", n <= 8, f"{n} of 16384 pixels differ (allowed 8)")


def case_intensity(run):
    """Light intensities of 1e30 and 1e-30: the image scales exactly and the
    stats' relative standard error stays that of the ordinary intensity."""
    base = load_scene("indirect")
    ref, rs = run.render(base, frames=4)
    i0 = base["light"]["intensity"]
    for i in (1e30, 1e-30):
        s = copy.deepcopy(base)
        s["light"]["intensity"] = i
        img, st = run.render(s, frames=4)
        n = differing_pixels(img, ref, levels=0.5, scale_b=i / i0)
        n = differing_pixels(ref, img, levels=0.5, scale_b=i0 / i) if n else n
        e0, e = rs.get("relative_standard_error"), st.get("relative_standard_error")
        ok_err = isinstance(e, (int, float)) and isinstance(e0, (int, float)) and e0 > 0 \
            and abs(e - e0) <= 1e-3 * e0
        yield (f"intensity {i:g}: image", n == 0, f"{n} pixels differ from the scaled image")
        yield (f"intensity {i:g}: relative standard error", ok_err, f"{e} against {e0}")


def case_denormals(run):
    """A closed diffuse sphere of albedo 0.75 at depth 1000: the throughput
    falls as 0.75^k and must reach zero (about 304 bounces in float without
    denormals), so the zero cut-off ends every path long before 1000."""
    s = scene_of("closed-0.75", [diffuse("shell", [0, 0, 0], 100, [0.75, 0.75, 0.75])],
                 camera((0, 0, 50), (0, 0, 0), 60, size=16),
                 {"position": [10, 20, 30], "intensity": 2e4},
                 max_depth=1000, indirect=True, split=1)
    img, st = run.render(s, "--split", "1")
    paths = 16 * 16
    per_path = st["rays"] / paths
    # ln(2^-126) / ln(0.75) = 303.6 bounces to the float minimum; each bounce
    # is one ray and one shadow ray, the camera ray and its shadow ray add 2.
    yield ("albedo 0.75 at depth 1000", per_path <= 2 * 310,
           f"{per_path:.1f} rays per path (at most {2 * 310} when denormals flush to zero)")
    yield ("albedo 0.75 at depth 1000: finite", st["nan_count"] == 0, f"nan_count {st['nan_count']}")


def closed_cube_obj(path, half, n):
    """An axis-aligned cube of half-size `half`, each face an n x n grid of
    quads split into triangles along alternating diagonals: many seams."""
    verts, index, faces = [], {}, []

    def vid(p):
        if p not in index:
            index[p] = len(verts) + 1
            verts.append(p)
        return index[p]
    for axis in range(3):
        for sign in (-1, 1):
            for a in range(n):
                for b in range(n):
                    def corner(u, v):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = sign * half
                        p[(axis + 1) % 3] = -half + 2 * half * u / n
                        p[(axis + 2) % 3] = -half + 2 * half * v / n
                        return vid(tuple(p))
                    q = (corner(a, b), corner(a + 1, b), corner(a + 1, b + 1), corner(a, b + 1))
                    if (a + b) % 2:
                        faces += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
                    else:
                        faces += [(q[0], q[1], q[3]), (q[1], q[2], q[3])]
    with open(path, "w") as f:
        for p in verts:
            f.write(f"v {p[0]!r} {p[1]!r} {p[2]!r}\n")
        for t in faces:
            f.write(f"f {t[0]} {t[1]} {t[2]}\n")


def icosphere_obj(path, radius, levels, jitter, seed=1):
    """A closed icosphere (20 * 4^levels triangles in every orientation), each
    vertex's distance from the centre varied by up to jitter / 2 of the radius."""
    import random
    t = (1 + 5 ** 0.5) / 2
    verts = [norm(v) for v in ((-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                               (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1))]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mids, finer = {}, []

        def mid(a, b):
            k = (min(a, b), max(a, b))
            if k not in mids:
                verts.append(norm(mul(add(verts[a], verts[b]), 0.5)))
                mids[k] = len(verts) - 1
            return mids[k]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = finer
    rnd = random.Random(seed)
    with open(path, "w") as f:
        for v in verts:
            f.write("v %r %r %r\n" % mul(v, radius * (1 + jitter * (rnd.random() - 0.5))))
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


def case_closed_mesh(run):
    """The camera inside a closed mesh, the light outside: black, with indirect
    light on; also moved to 1e5 and scaled to 1e-4."""
    obj = run.dir / "cube.obj"
    closed_cube_obj(obj, 20.0, 7)
    mesh = {"name": "box", "path": str(obj), "material": {"type": "diffuse", "albedo": [0.9, 0.9, 0.9]}}
    s = scene_of("closed-box", [diffuse("ball", [0, -10, 0], 5, [1, 1, 1])],
                 camera((3, 4, 15), (0, -5, 0), 100), {"position": [30, 35, 40], "intensity": 2e10},
                 meshes=[mesh], indirect=True)
    for what, sc in (("at the origin", s), ("moved by 1e5", translated(s, (1e5, -1e5, 1e5))),
                     ("scaled by 1e-4", scaled(s, 1e-4))):
        img, st = run.render(sc, spp=4)
        lit = sum(1 for row in img["px"] for p in row if any(v != 0 for v in p))
        yield (f"camera inside a closed mesh, light outside, {what}", lit == 0,
               f"{lit} pixels not black")
    # A lumpy icosphere: seams in every orientation, none axis-aligned.
    obj = run.dir / "ico.obj"
    icosphere_obj(obj, 20.0, 2, 0.3)
    mesh = {"name": "ico", "path": str(obj), "material": {"type": "diffuse", "albedo": [0.9, 0.9, 0.9]}}
    s = scene_of("closed-ico", [diffuse("ball", [0, -5, 0], 4, [1, 1, 1])],
                 camera((3, 4, 8), (0, -5, 0), 120), {"position": [30, 35, 40], "intensity": 2e10},
                 meshes=[mesh], indirect=True)
    for what, sc in (("at the origin", s), ("moved by 9.99e6", translated(s, (9.99e6, -9.99e6, 9.99e6))),
                     ("scaled by 1e-5", scaled(s, 1e-5)), ("scaled by 1e4", scaled(s, 1e4))):
        img, st = run.render(sc, spp=2)
        lit = sum(1 for row in img["px"] for p in row if any(v != 0 for v in p))
        yield (f"camera inside a closed icosphere, light outside, {what}", lit == 0,
               f"{lit} pixels not black")


def case_degenerate_mesh(run):
    """Zero-area triangles (repeated and collinear corners) beside a real one
    change nothing and produce no NaN."""
    good = "v -20 -10 -20\nv 20 -10 -20\nv 0 15 -20\n"
    a, b = run.dir / "tri.obj", run.dir / "tri-degenerate.obj"
    a.write_text(good + "f 1 2 3\n")
    b.write_text(good + "v 5 5 -10\nv 5 5 -10\nv 10 10 -10\nv 0 0 -10\n"
                 "f 1 2 3\nf 4 5 6\nf 4 4 4\nf 1 2 1\nf 4 6 7\nf 7 7 4\n")
    mk = lambda p: scene_of("tri", room(), camera((0, 0, 55), (0, 0, 0), 60),
                            {"position": [-10, 20, 40], "intensity": 2e10},
                            meshes=[{"name": "t", "path": str(p),
                                     "material": {"type": "diffuse", "albedo": [1, 1, 1]}}],
                            indirect=True)
    ref, _ = run.render(mk(a), spp=2)
    img, st = run.render(mk(b), spp=2)
    n = differing_pixels(img, ref, levels=0.0)
    yield ("degenerate triangles beside a real one", n == 0 and st["nan_count"] == 0,
           f"{n} pixels differ, nan_count {st['nan_count']}")
    # A mesh with no triangle of non-zero area is refused, by name, not drawn as nothing.
    c = run.dir / "all-degenerate.obj"
    c.write_text("v 1 1 1\nv 1 1 1\nv 2 2 2\nv 3 3 3\nf 1 2 3\nf 2 3 4\n")
    try:
        run.render(mk(c))
        refused, msg = False, "rendered"
    except RuntimeError as e:
        msg = str(e).strip().splitlines()[-1]
        refused = "all-degenerate.obj" in msg and "no triangles with non-zero area" in msg
    yield ("a mesh of only degenerate triangles is refused", refused, msg[-120:])


def case_extreme_glass(run):
    """The camera inside a glass ball, indices from barely above 1 to the
    reader's largest: every sample finite."""
    for ior in (1.0, 1.0001, 4.0):
        for fresnel in ("off", "on"):
            s = scene_of("inside-glass", room() + [
                {"name": "g", "center": [0, 0, 45], "radius": 15,
                 "material": {"type": "glass", "ior": ior}}],
                camera((0, 0, 55), (0, 0, 0), 60), {"position": [-10, 20, 40], "intensity": 2e10},
                indirect=True, max_depth=20)
            img, st = run.render(s, "--fresnel", fresnel, spp=2)
            finite = all(math.isfinite(v) for row in img["px"] for p in row for v in p)
            yield (f"camera in glass ior {ior}, fresnel {fresnel}", finite and st["nan_count"] == 0,
                   f"nan_count {st['nan_count']}, finite {finite}")


def case_light_in_cage(run):
    """A light inside a small closed ball, the camera outside: nothing is lit
    (the closed form), whatever the ball's size against the light's distance,
    also moved by 1e6; and inside a small closed cube mesh."""
    walls, cam, light = room(), camera((0, 0, 55), (0, 0, 0), 60), (-10.0, 20.0, 40.0)
    # Radii down to 1e-4, about 2e-6 of the light's distance from the
    # camera: smaller, the float positions of render space cannot tell a
    # light inside a ball from one on its surface (docs/NUMERICS.md).
    for r, shift, k in ((1e-2, 0.0, 1.0), (1e-3, 0.0, 1.0), (1e-4, 0.0, 1.0), (1e-4, 1e6, 1.0),
                        (1e-4, 0.0, 1e-2)):
        s = scene_of("light-in-cage", walls + [diffuse("cage", list(light), r, [1, 1, 1]),
                                               diffuse("ball", [0, 0, 0], 10, [1, 1, 1])],
                     cam, {"position": list(light), "intensity": 2e10})
        img, _ = run.render(translated(scaled(s, k), (shift, shift, shift)))
        lit = sum(1 for row in img["px"] for p in row if any(v != 0 for v in p))
        at = (f", moved by {shift:g}" if shift else "") + (f", all scaled by {k:g}" if k != 1 else "")
        yield (f"light inside a ball of radius {r:g} of the scale{at}", lit == 0,
               f"{lit} pixels not black")
    obj = run.dir / "cage.obj"
    closed_cube_obj(obj, 1e-2, 2)
    s = scene_of("light-in-mesh-cage", walls + [diffuse("ball", [0, 0, 0], 10, [1, 1, 1])], cam,
                 {"position": list(light), "intensity": 2e10},
                 meshes=[{"name": "cage", "path": str(obj), "translate": list(light),
                          "material": {"type": "diffuse", "albedo": [1, 1, 1]}}])
    img, _ = run.render(s)
    lit = sum(1 for row in img["px"] for p in row if any(v != 0 for v in p))
    yield ("light inside a closed cube mesh of half-size 1e-2", lit == 0, f"{lit} pixels not black")


def floor_quad_obj(path, half, y):
    """Two triangles, the square |x|, |z| <= half at height y, facing up."""
    path.write_text(f"v {-half!r} {y!r} {-half!r}\nv {half!r} {y!r} {-half!r}\n"
                    f"v {half!r} {y!r} {half!r}\nv {-half!r} {y!r} {half!r}\nf 1 3 2\nf 1 4 3\n")


def case_huge_mesh(run):
    """A ground of two triangles 2e4 and 2e5 across (vertices exact in float),
    a ball of radius 1 resting on it, seen from a few units away: against the
    double-precision reference's plane."""
    light = (2.0, 5.0, 1.0)
    # Not beyond 1e5: a triangle 2e6 across has a spawn offset of about 0.8
    # (docs/NUMERICS.md, "What it does not do").
    for half in (1e4, 1e5):
        obj = run.dir / f"ground-{half:g}.obj"
        floor_quad_obj(obj, half, -1.0)
        for cam_at in ((0.0, 0.0, 5.0), (3.0, 0.5, 3.0)):
            cam = camera(cam_at, (0, -0.5, 0), 90)
            s = scene_of("huge-ground", [diffuse("ball", [0, 0, 0], 1, [1, 1, 1])], cam,
                         {"position": list(light), "intensity": 2e7},
                         meshes=[{"name": "ground", "path": str(obj),
                                  "material": {"type": "diffuse", "albedo": [1, 1, 1]}}])
            img, _ = run.render(s)
            ref, amb = Reference([((0.0, 0.0, 0.0), 1.0, (1, 1, 1))],
                                 [((0.0, -1.0, 0.0), (0.0, 1.0, 0.0), (1, 1, 1), half)],
                                 light, 2e7).image(cam)
            n = wrong_against_reference(img, ref, amb)
            yield (f"ground {2 * half:g} across, camera at {cam_at}", n <= 2,
                   f"{n} pixels off the reference (allowed 2)")


def case_glass_far(run):
    """The camera inside a glass ball: with index 1 and no Fresnel against the
    see-through reference (the ball bends nothing but blocks shadow rays);
    with indices 1.0001 and 4, the scene moved by 1e6 or scaled by 1e-5 and
    1e4 renders as at the origin."""
    walls = room()
    ref_walls = [(tuple(w["center"]), w["radius"], tuple(w["material"]["albedo"])) for w in walls]
    for centre, radius in (((0.0, 0.0, 45.0), 15.0), ((0.0, 0.0, 50.0), 8.0)):
        def mk(ior):
            return scene_of("glass-far", copy.deepcopy(walls) + [
                {"name": "g", "center": list(centre), "radius": radius,
                 "material": {"type": "glass", "ior": ior}},
                diffuse("ball", [10, -5, -10], 5, [1, 1, 1])],
                camera((0, 0, 55), (0, 0, 0), 60), {"position": [-10, 20, 40], "intensity": 2e10},
                max_depth=30)
        img, _ = run.render(mk(1.0), "--fresnel", "off")
        ref, amb = Reference(ref_walls + [((10.0, -5.0, -10.0), 5.0, (1, 1, 1))], [], (-10.0, 20.0, 40.0),
                             2e10, shadow_only=[(centre, radius)]).image(mk(1.0)["camera"])
        n = wrong_against_reference(img, ref, amb)
        yield (f"camera in glass r={radius:g}, ior 1, against the see-through reference", n <= 2,
               f"{n} pixels off (allowed 2)")
        for ior in (1.0001, 4.0):
            base, _ = run.render(mk(ior), "--fresnel", "off")
            for what, sc in (("moved by 1e6", translated(mk(ior), (1e6, -1e6, 1e6))),
                             ("scaled by 1e-5", scaled(mk(ior), 1e-5)),
                             ("scaled by 1e4", scaled(mk(ior), 1e4))):
                img, st = run.render(sc, "--fresnel", "off")
                n = differing_pixels(img, base)
                yield (f"camera in glass r={radius:g}, ior {ior:g}, {what}", n <= 8 and st["nan_count"] == 0,
                       f"{n} of 4096 pixels differ (allowed 8), nan_count {st['nan_count']}")


def case_noise_free_error(run):
    """A noise-free image (direct light at pixel centres) has a relative
    standard error of 0 at every intensity: the stats must not report the
    rounding of their own sums as noise."""
    base = load_scene("three-balls")
    for i in (2e10, 1e30, 1e-30):
        s = copy.deepcopy(base)
        s["light"]["intensity"] = i
        _, st = run.render(s, spp=4)
        e = st.get("relative_standard_error")
        yield (f"three-balls, intensity {i:g}: relative standard error", isinstance(e, (int, float)) and e <= 1e-6,
               f"{e} (a noise-free image: at most 1e-6)")


def subdivided_obj(src, dst):
    """Each triangle of an OBJ split in four at its edge midpoints (in double)."""
    verts, faces = [], []
    for line in open(src):
        if line.startswith("v "):
            verts.append(tuple(float(v) for v in line.split()[1:4]))
        elif line.startswith("f "):
            faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:4]])
    out, mids = list(verts), {}

    def mid(a, b):
        k = (min(a, b), max(a, b))
        if k not in mids:
            out.append(tuple(0.5 * (x + y) for x, y in zip(verts[a], verts[b])))
            mids[k] = len(out) - 1
        return mids[k]
    with open(dst, "w") as f:
        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        for v in out:
            f.write("v %r %r %r\n" % v)
        for t in new:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    return len(faces), len(new)


def case_subdivided_cat(run):
    """The report's program scales a triangle's light by twice its area (an
    unnormalised cross product): the cat with every triangle split in four
    must render the same, direct light and with indirect light and
    anti-aliasing (the same samples: only rounding may differ)."""
    fine = run.dir / "cat-fine.obj"
    n0, n1 = subdivided_obj(CAT_OBJ, fine)
    for what, flags in (("direct light", ["--indirect", "off", "--aa", "off"]),
                        ("indirect light and anti-aliasing", [])):
        base = load_scene("cat")
        ref, _ = run.render(base, *flags, spp=4)
        s = copy.deepcopy(base)
        s["meshes"][0]["path"] = str(fine)
        img, _ = run.render(s, *flags, spp=4)
        n = differing_pixels(img, ref)
        mr, mi = image_mean(ref), image_mean(img)
        yield (f"cat split into {n1} triangles ({n0} before), {what}",
               n <= 8 and abs(mi - mr) <= 2e-3 * mr,
               f"{n} of 4096 pixels differ (allowed 8); mean {mi:.6g} against {mr:.6g}")


def case_vertex_normals(run):
    """An OBJ's vertex normals of any length shade as unit ones: a quad whose
    normals are all (0, 1, 0) times 1e30, 1e20, 1e-23 or 1e-30 (float squares
    overflow or underflow) renders as with unit normals, with indirect light
    (NaN shading normals gave NaN bounce rays, which crashed the traversal);
    and a zero normal at one corner adds nothing: no NaN, the same image."""
    def quad(path, normals):
        path.write_text("v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\n" +
                        "".join(f"vn {a!r} {b!r} {c!r}\n" for a, b, c in normals) +
                        "f 1//1 3//3 2//2\nf 1//1 4//4 3//3\n")

    def mk(path):
        return scene_of("vertex-normals", [diffuse("ball", [0, 2, 0], 2, [1, 1, 1])],
                        camera((0, 8, 12), (0, 0, 0), 60), {"position": [3, 10, 4], "intensity": 2e4},
                        meshes=[{"name": "quad", "path": str(path), "vertex_normals": True,
                                 "material": {"type": "diffuse", "albedo": [1, 1, 1]}}],
                        indirect=True)
    unit = run.dir / "quad-unit.obj"
    quad(unit, [(0.0, 1.0, 0.0)] * 4)
    ref, _ = run.render(mk(unit), spp=2)
    for what, normals in [(f"normals {k:g} long", [(0.0, k, 0.0)] * 4) for k in (1e30, 1e20, 1e-23, 1e-30)] + [
            ("a zero normal at one corner", [(0.0, 1.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 1.0, 0.0)])]:
        path = run.dir / f"quad-{len(what)}-{what[:12].replace(' ', '_')}.obj"
        quad(path, normals)
        try:
            img, st = run.render(mk(path), spp=2)
        except RuntimeError as e:
            yield (f"quad with {what}", False, str(e)[-120:])
            continue
        n = differing_pixels(img, ref, levels=0.5)
        yield (f"quad with {what}", n == 0 and st["nan_count"] == 0,
               f"{n} of 4096 pixels differ from unit normals, nan_count {st['nan_count']}")


CASES = {
    "offset": case_offset,
    "scale": case_scale,
    "small-far": case_small_far,
    "thin-shell": case_thin_shell,
    "tiny-ball": case_tiny_ball,
    "light-on-surface": case_light_on_surface,
    "light-exactly-on-surface": case_light_exactly_on_surface,
    "far-obj": case_far_obj,
    "intensity": case_intensity,
    "denormals": case_denormals,
    "closed-mesh": case_closed_mesh,
    "degenerate-mesh": case_degenerate_mesh,
    "extreme-glass": case_extreme_glass,
    "light-in-cage": case_light_in_cage,
    "huge-mesh": case_huge_mesh,
    "glass-far": case_glass_far,
    "noise-free-error": case_noise_free_error,
    "subdivided-cat": case_subdivided_cat,
    "vertex-normals": case_vertex_normals,
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--whisker", required=True)
    ap.add_argument("--case", action="append", choices=sorted(CASES))
    ap.add_argument("--keep", help="keep scenes and images in this folder")
    args = ap.parse_args()
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(args.keep or tmp)
        work.mkdir(parents=True, exist_ok=True)
        run = Runner(os.path.abspath(args.whisker), work)
        for name in args.case or sorted(CASES):
            for what, ok, detail in CASES[name](run):
                print(f"{'ok  ' if ok else 'FAIL'} {name}: {what}: {detail}", flush=True)
                failed += not ok
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
