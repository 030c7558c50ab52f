#!/usr/bin/env python3
"""Stress csgrt's intersections against exact arithmetic.

For every primitive (sphere, cube, cylinder, cone, frustum, torus), placed at
offsets 0, 1e3 and 1e6 from the origin and at sizes 1e-3, 1 and 1e3, rays of
several kinds are traced by csgrt (--trace-rays) and by mpmath at 50 digits
from the very same f64 inputs:

* random: from 3 sizes away towards random points of the solid;
* grazing: passing 1e-9 of the size inside the outline (a sphere's or a
  cylinder's side, a torus's outer equator, a cone's slant);
* edge: parallel to a box edge, 1e-9 of the size inside both faces;
* corner: aimed past a box corner, 1e-9 of the size inside it along the
  diagonal.
  Where 1e-9 of the size is finer than the f64 coordinates there can say
  (a 1e-3 part at 1e6, where one ulp is 1.2e-10), the ray passes 8 ulps of
  those coordinates inside instead: the closest to tangent a ray can be
  placed there;
* inside: from inside the solid outwards.

The distance error is relative to the ray's length scale, max(t, size); it
must stay at most 1e-9, and csgrt must hit where the exact ray hits. The
report (--report) gives the worst error per primitive and case.

Usage: accuracy.py [--csgrt BIN] [--rays N] [--check] [--report FILE]
"""

import argparse
import math
import os
import random
import subprocess
import sys
import tempfile

import mpmath as mp

mp.mp.dps = 50
LIMIT = 1e-9
OFFSETS = [0.0, 1e3, 1e6]
SIZES = [1e-3, 1.0, 1e3]
SLIM = 1e-9  # how far inside the outline grazing rays pass, in sizes


def M(x):
    return mp.mpf(x)


def v3(a):
    return [M(x) for x in a]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def unit(v):
    """A unit direction rounded to f64, as the ray file will carry it."""
    n = mp.sqrt(dot(v, v))
    return [float(x / n) for x in v]


# --------------------------------------------------------------------------
# Primitives: csgrt text and exact first crossings
# --------------------------------------------------------------------------


class Prim:
    """A primitive of size s centred near c (all floats, exact in f64)."""

    def __init__(self, kind, c, s):
        self.kind, self.c, self.s = kind, c, s

    def text(self):
        c = ", ".join(repr(x) for x in self.c)
        s = repr(self.s)
        body = {
            "sphere": f"sphere(r = {s});",
            "cube": f"cube({s}, center = true);",
            "cylinder": f"cylinder(h = {s}, r = {repr(self.s / 2)}, center = true);",
            "cone": f"cylinder(h = {s}, r1 = {repr(self.s / 2)}, r2 = 0, center = true);",
            "frustum": f"cylinder(h = {s}, r1 = {repr(self.s / 2)}, r2 = {repr(self.s / 4)}, center = true);",
            "torus": f"torus(R = {s}, r = {repr(self.s / 4)});",
        }[self.kind]
        return f"translate([{c}]) {body}\n"

    def crossings(self, o, d):
        """Sorted exact t of every boundary crossing of the line."""
        o = [M(o[i]) - M(self.c[i]) for i in range(3)]
        d = v3(d)
        s = M(self.s)
        k = self.kind
        if k == "sphere":
            return quadratic(dot(d, d), dot(o, d), dot(o, o) - s * s)
        if k == "cube":
            h = s / 2
            lo, hi = -mp.inf, mp.inf
            for i in range(3):
                if d[i] == 0:
                    if abs(o[i]) >= h:
                        return []
                    continue
                a, b = (-h - o[i]) / d[i], (h - o[i]) / d[i]
                lo, hi = max(lo, min(a, b)), min(hi, max(a, b))
            return [lo, hi] if lo < hi else []
        if k in ("cylinder", "cone", "frustum"):
            h = s / 2
            r0 = s / 2
            r1 = {"cylinder": s / 2, "cone": M(0), "frustum": s / 4}[k]
            kk = (r1 - r0) / s  # radius change per unit height, z from -h
            # x^2 + y^2 = (r0 + kk (z + h))^2 within -h <= z <= h
            rz0 = r0 + kk * (o[2] + h)
            a = d[0] ** 2 + d[1] ** 2 - kk * kk * d[2] ** 2
            b = o[0] * d[0] + o[1] * d[1] - kk * d[2] * rz0
            c = o[0] ** 2 + o[1] ** 2 - rz0 * rz0
            if d[2] == 0:
                if abs(o[2]) >= h:
                    return []
                zlo, zhi = -mp.inf, mp.inf
            else:
                ta, tb = (-h - o[2]) / d[2], (h - o[2]) / d[2]
                zlo, zhi = min(ta, tb), max(ta, tb)
            pieces = side_pieces(a, b, c)
            for lo, hi in pieces:
                lo, hi = max(lo, zlo), min(hi, zhi)
                if lo < hi:
                    return [lo, hi]
            return []
        if k == "torus":
            R, r = s, s / 4
            # (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) as a quartic in t
            A, B, C = dot(d, d), 2 * dot(o, d), dot(o, o) + R * R - r * r
            axy = d[0] ** 2 + d[1] ** 2
            bxy = 2 * (o[0] * d[0] + o[1] * d[1])
            cxy = o[0] ** 2 + o[1] ** 2
            coeffs = [
                A * A,
                2 * A * B,
                B * B + 2 * A * C - 4 * R * R * axy,
                2 * B * C - 4 * R * R * bxy,
                C * C - 4 * R * R * cxy,
            ]
            roots = mp.polyroots(coeffs, maxsteps=200, extraprec=200)
            real = sorted(mp.re(x) for x in roots if abs(mp.im(x)) < mp.mpf(10) ** -30)
            return real
        raise ValueError(k)

    def first(self, o, d):
        ts = [t for t in self.crossings(o, d) if t > 0]
        return ts[0] if ts else None


def quadratic(a, b, c):
    """Roots of a t^2 + 2 b t + c = 0 when two distinct real ones exist."""
    disc = b * b - a * c
    if disc <= 0:
        return []
    q = mp.sqrt(disc)
    return sorted([(-b - q) / a, (-b + q) / a])


def side_pieces(a, b, c):
    """Intervals of t where a t^2 + 2 b t + c <= 0."""
    if a == 0:
        if b > 0:
            return [(-mp.inf, -c / (2 * b))]
        if b < 0:
            return [(-c / (2 * b), mp.inf)]
        return [(-mp.inf, mp.inf)] if c < 0 else []
    disc = b * b - a * c
    if disc < 0:
        return [(-mp.inf, mp.inf)] if a < 0 else []
    q = mp.sqrt(disc)
    lo, hi = sorted([(-b - q) / a, (-b + q) / a])
    return [(lo, hi)] if a > 0 else [(-mp.inf, lo), (hi, mp.inf)]


# --------------------------------------------------------------------------
# Rays
# --------------------------------------------------------------------------


def rays_for(p, n, rng):
    """(case, origin, direction) triples, all floats."""
    c, s = p.c, p.s
    out = []

    def at(*rel):
        return [c[i] + rel[i] * s for i in range(3)]

    for _ in range(n):
        u = [rng.gauss(0, 1) for _ in range(3)]
        nu = sum(x * x for x in u) ** 0.5
        o = at(*(3 * x / nu for x in u))
        target = at(*(rng.uniform(-0.3, 0.3) for _ in range(3)))
        out.append(("random", o, unit([target[i] - o[i] for i in range(3)])))
        inner = at(*(rng.uniform(-0.05, 0.05) for _ in range(3)))
        if p.kind == "torus":
            inner = at(1.0, 0.0, rng.uniform(-0.05, 0.05))
        out.append(("inside", inner, unit(u)))
    k = p.kind
    ulp = math.ulp(max(abs(x) for x in c) or 1.0)
    slim = 1 - max(SLIM, 8 * ulp / s)
    for j in range(n):
        a = 2 * mp.pi * j / n
        if k == "sphere":
            # A tangent line at distance s(1 - 1e-9) from the centre.
            r = s * slim
            e1 = [mp.cos(a), mp.sin(a), 0]
            o = at(*(float(r / s * e1[i]) + (-3.0 if i == 2 else 0.0) for i in range(3)))
            out.append(("grazing", o, [0.0, 0.0, 1.0]))
        elif k in ("cylinder", "cone", "frustum"):
            # Across the side at mid-height, 1e-9 inside the outline.
            rmid = {"cylinder": 0.5, "cone": 0.25, "frustum": 0.375}[k]
            y = float(rmid * slim)
            o = at(-3.0, y, float(0.1 * mp.sin(a)))
            out.append(("grazing", o, [1.0, 0.0, 0.0]))
        elif k == "torus":
            # Along x, 1e-9 inside the outer equator (|y| = 1.25 s).
            o = at(-3.0, float(1.25 * slim), 0.0)
            out.append(("grazing", o, unit([1.0, float(1e-3 * mp.sin(a)), 0.0])))
        elif k == "cube":
            e = float(0.5 * slim)
            sx, sy = (1 if j % 2 else -1), (1 if (j // 2) % 2 else -1)
            out.append(("edge", at(sx * e, sy * e, -3.0), [0.0, 0.0, 1.0]))
            corner = at(sx * e, sy * e, e)
            o = at(sx * 3.0, sy * 2.0, 3.5)
            out.append(("corner", o, unit([corner[i] - o[i] for i in range(3)])))
    return out


# --------------------------------------------------------------------------


def run(binary, prim, rays, work):
    scene = os.path.join(work, "s.csg")
    with open(scene, "w") as f:
        f.write(prim.text())
    rf = os.path.join(work, "rays.txt")
    with open(rf, "w") as f:
        for _, o, d in rays:
            f.write(" ".join(repr(float(x)) for x in (*o, *d)) + "\n")
    out = subprocess.run([binary, scene, "--trace-rays", rf], check=True, capture_output=True, text=True)
    return [None if line == "miss" else float(line.split()[0]) for line in out.stdout.splitlines()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default="target/release/csgrt")
    ap.add_argument("--rays", type=int, default=12)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--report", default=None)
    a = ap.parse_args()
    rng = random.Random(20261122)
    worst = {}  # (kind, case) -> (error, description)
    failures = []
    direction = [1.0, 0.7, 0.3]
    with tempfile.TemporaryDirectory() as work:
        for kind in ["sphere", "cube", "cylinder", "cone", "frustum", "torus"]:
            for off in OFFSETS:
                for size in SIZES:
                    p = Prim(kind, [off * x for x in direction], size)
                    rays = rays_for(p, a.rays, rng)
                    got = run(a.csgrt, p, rays, work)
                    for (case, o, d), t in zip(rays, got):
                        exact = p.first(o, d)
                        where = f"{kind} size {size:g} at offset {off:g}, {case} ray {' '.join(repr(x) for x in (*o, *d))}"
                        if (exact is None) != (t is None):
                            failures.append(f"{where}: csgrt {t}, exact {exact}")
                            err = float("inf")
                        elif exact is None:
                            continue
                        else:
                            scale = max(exact, M(size))
                            err = float(abs(M(t) - exact) / scale)
                        key = (kind, case)
                        if err > worst.get(key, (-1.0, ""))[0]:
                            worst[key] = (err, where)
                        if err > LIMIT and err != float("inf"):
                            failures.append(f"{where}: relative error {err:.3g} > {LIMIT:g}")
    lines = [
        "# Accuracy against exact arithmetic",
        "",
        "Generated by `tools/accuracy.py --report docs/accuracy.md`: csgrt's `--trace-rays` against",
        "mpmath at 50 digits, from the same f64 rays. Each primitive is placed at offsets 0, 1e3 and",
        "1e6 and sized 1e-3, 1 and 1e3; the error is |t - t_exact| / max(t_exact, size). The limit is",
        f"{LIMIT:g}.",
        "",
        "| primitive | case | worst relative error | where |",
        "|---|---|---|---|",
    ]
    for (kind, case), (err, where) in sorted(worst.items()):
        lines.append(f"| {kind} | {case} | {err:.3g} | {where.split(',')[0]} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if a.report:
        with open(a.report, "w") as f:
            f.write(text)
    for f in failures[:20]:
        print("FAIL", f, file=sys.stderr)
    print(f"{len(worst)} cases, {len(failures)} failures")
    if a.check and failures:
        sys.exit(1)


if __name__ == "__main__":
    main()
