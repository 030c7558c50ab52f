#!/usr/bin/env python3
"""Stress csgrt's intersections against exact arithmetic.

For every primitive (sphere, cube, cylinder, cone, frustum, torus, and the
extrusions: a straight, a tapered and a twisted prism of an L-shaped polygon,
a glyph's prism — quadratic Bézier edges, the letter from the built-in font
laid out by tools/oracle/scene/ — and an L profile turned), placed at
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
import atexit
import math
import multiprocessing
import os
import random
import shutil
import subprocess
import sys
import tempfile

import mpmath as mp


mp.mp.dps = 50
LIMIT = 1e-9
OFFSETS = [0.0, 1e3, 1e6]
SIZES = [1e-3, 1.0, 1e3]
SLIM = 1e-9  # how far inside the outline grazing rays pass, in sizes
ANGLE_FLOOR = 1e-12  # radians: rounding of unit vectors and of the pose


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


def rotation(deg):
    """OpenSCAD's rotate([x, y, z]): Rz Ry Rx, exact at 50 digits."""
    out = [[M(i == j) for j in range(3)] for i in range(3)]
    for axis in (0, 1, 2):
        a = mp.pi * M(deg[axis]) / 180
        c, s = mp.cos(a), mp.sin(a)
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        r = [[M(k == m) for m in range(3)] for k in range(3)]
        r[i][i], r[i][j], r[j][i], r[j][j] = c, -s, s, c
        out = matmul(r, out)
    return out


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(m):
    return [[m[j][i] for j in range(3)] for i in range(3)]


# How a primitive is posed: rotate(angles) scale(factors), then translated.
POSES = {
    "plain": None,
    "rotated": ([30.0, 50.0, 20.0], [1.0, 1.0, 1.0]),
    "scaled": ([0.0, 0.0, 0.0], [1.5, 0.625, 1.125]),
    "rotated+scaled": ([-40.0, 25.0, 70.0], [0.75, 1.25, 1.875]),
}


class Prim:
    """A primitive of size s centred near c (all floats, exact in f64),
    posed by `translate(c) rotate(angles) scale(factors)`."""

    def __init__(self, kind, c, s, pose="plain"):
        self.kind, self.c, self.s, self.pose = kind, c, s, pose
        if POSES[pose] is None:
            self.lin = [[M(i == j) for j in range(3)] for i in range(3)]
        else:
            angles, factors = POSES[pose]
            self.lin = matmul(rotation(angles), [[M(factors[i]) if i == j else M(0) for j in range(3)] for i in range(3)])
        self.inv = mp.matrix(self.lin) ** -1
        self.inv = [[self.inv[i, j] for j in range(3)] for i in range(3)]
        sv = mp.svd_r(mp.matrix(self.lin), compute_uv=False)
        self.smax, self.smin = max(sv), min(sv)

    def place(self, o, d):
        """A ray given in the unposed frame (around c), posed, as floats."""
        rel = [M(o[i]) - M(self.c[i]) for i in range(3)]
        po = apply(self.lin, rel)
        return [float(M(self.c[i]) + po[i]) for i in range(3)], unit(apply(self.lin, v3(d)))

    def text(self):
        body = self.body()
        c = ", ".join(repr(x) for x in self.c)
        if POSES[self.pose] is None:
            return f"translate([{c}]) {body}\n"
        angles, factors = POSES[self.pose]
        a = ", ".join(repr(x) for x in angles)
        f = ", ".join(repr(x) for x in factors)
        return f"translate([{c}]) rotate([{a}]) scale([{f}]) {body}\n"

    def local(self, o, d):
        rel = [M(o[i]) - M(self.c[i]) for i in range(3)]
        return apply(self.inv, rel), apply(self.inv, v3(d))

    def normal(self, o, d, t):
        """The exact unit outward normal where the ray crosses at t, and the
        smallest curvature radius there (object units)."""
        lo, ld = self.local(o, d)
        p = [lo[i] + t * ld[i] for i in range(3)]
        s, k = M(self.s), self.kind
        if k == "sphere":
            n, rho = p, s
        elif k == "cube":
            i = max(range(3), key=lambda i: abs(p[i]))
            n, rho = [M(0)] * 3, mp.inf
            n[i] = mp.sign(p[i])
        elif k in ("cylinder", "cone", "frustum"):
            h, r0 = s / 2, s / 2
            r1 = {"cylinder": s / 2, "cone": M(0), "frustum": s / 4}[k]
            kk = (r1 - r0) / s
            rz = r0 + kk * (p[2] + h)
            rxy = mp.sqrt(p[0] ** 2 + p[1] ** 2)
            dist = [abs(p[2] + h), abs(p[2] - h), abs(rxy - rz)]
            j = min(range(3), key=lambda j: dist[j])
            if j < 2:
                n, rho = [M(0), M(0), M(-1 if j == 0 else 1)], mp.inf
            else:
                n, rho = [p[0], p[1], -kk * rz], rxy
        else:
            R, r = s, s / 4
            q = p[0] ** 2 + p[1] ** 2 + p[2] ** 2 + R * R - r * r
            n = [4 * q * p[0] - 8 * R * R * p[0], 4 * q * p[1] - 8 * R * R * p[1], 4 * q * p[2]]
            rho = min(r, R - r)
        w = apply(transpose(self.inv), n)
        ln = mp.sqrt(dot(w, w))
        return [x / ln for x in w], rho

    def body(self):
        s = repr(self.s)
        return {
            "sphere": f"sphere(r = {s});",
            "cube": f"cube({s}, center = true);",
            "cylinder": f"cylinder(h = {s}, r = {repr(self.s / 2)}, center = true);",
            "cone": f"cylinder(h = {s}, r1 = {repr(self.s / 2)}, r2 = 0, center = true);",
            "frustum": f"cylinder(h = {s}, r1 = {repr(self.s / 2)}, r2 = {repr(self.s / 4)}, center = true);",
            "torus": f"torus(R = {s}, r = {repr(self.s / 4)});",
        }[self.kind]

    def crossings(self, o, d):
        """Sorted exact t of every boundary crossing of the line."""
        o, d = self.local(o, d)
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
            return torus_crossings(o, d, s, s / 4)
        raise ValueError(k)

    def first(self, o, d):
        ts = [t for t in self.crossings(o, d) if t > 0]
        return ts[0] if ts else None


# --------------------------------------------------------------------------
# Extrusions: exact crossings of prisms, tapered, twisted and turned
# polygons, and a glyph's curves
# --------------------------------------------------------------------------

L_SHAPE = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.0), (0.0, 0.0), (0.0, 0.5), (-0.5, 0.5)]
PROFILE = [(0.25, -0.5), (0.5, -0.5), (0.5, 0.0), (0.375, 0.25), (0.25, 0.5)]
EXTRUSIONS = ["prism", "tapered", "twisted", "twisted_ellipse", "glyph", "cubic", "lathe", "turned_cubic", "offset_glyph"]
# The turned cubic profile: a vase's half section in the file (x, y), read
# as (r, z) = (x, -y) (no page size), times the size over 60.
VASE = [((5, 30),), ((20, 30), (32, 10), (8, -10)), ((18, -30),), ((15, -30), (4, -12), (28, 10)), ((5, 26),)]
# The cubic prism: an SVG path of two cubic Bézier curves and two lines
# (file units, times the size; y points down in the file, up once read).
CUBIC_PATH = [((-0.4, -0.3), (-0.1, -0.6), (0.3, 0.1)), ((0.4, -0.35),), ((0.45, 0.3), (0.1, 0.0), (-0.2, 0.6)), ((-0.45, 0.25),)]
_SVG_DIR = []


def svg_dir():
    """A temporary directory for the SVG files of the cases, made by the
    first case that needs one and removed when this process exits (an
    importer such as explain_shadows.py makes none)."""
    if not _SVG_DIR:
        _SVG_DIR.append(tempfile.mkdtemp(prefix="csgrt-accuracy-"))
        atexit.register(shutil.rmtree, _SVG_DIR[0], True)
    return _SVG_DIR[0]


# The twisted ellipse: the unit circle under x -> A x + c (times the size).
ELLIPSE_A, ELLIPSE_C = ((0.3, 0.12), (-0.05, 0.2)), (0.12, 0.08)
TAPER = 0.5
TWIST, TWIST_SCALE = 90.0, (0.7, 1.3)


def cross2(a, b):
    return a[0] * b[1] - a[1] * b[0]


class Extruded(Prim):
    """A 2-D shape of size s extruded over z in [-s/2, s/2] (straight,
    tapered to TAPER, twisted by TWIST with TWIST_SCALE) or turned (its
    profile in (r, z)), centred at c."""

    def __init__(self, kind, c, s, pose="plain"):
        super().__init__(kind, c, s, pose)
        self.h = M(s) / 2
        if kind == "glyph":
            from tools.oracle import scene as reader

            with tempfile.NamedTemporaryFile("w", suffix=".csg", delete=False) as f:
                f.write(self.body() + "\n")
            leaf = reader.read(f.name).leaves[0]
            os.unlink(f.name)
            flat = leaf.params["flat"]
            parts = flat[2] if flat[0] == "op" else [flat]
            self.edges = []
            for g in parts:
                for a, c_, b in reader.curve_pieces(g):
                    pts = [a, b] if c_ is None else [a, c_, b]
                    self.edges.append([[M(float(x)) for x in q] for q in pts])
        elif kind == "cubic":
            # Points of the file at x, y are read at (x, -y) (no page size).
            pts = [[float(x * s) for x in q] for seg in CUBIC_PATH for q in seg]
            self.svg = os.path.join(svg_dir(), f"cubic_{s!r}.svg")
            d = f"M {pts[0][0]!r} {pts[0][1]!r} C {pts[1][0]!r} {pts[1][1]!r} {pts[2][0]!r} {pts[2][1]!r} {pts[3][0]!r} {pts[3][1]!r} L {pts[4][0]!r} {pts[4][1]!r} C {pts[5][0]!r} {pts[5][1]!r} {pts[6][0]!r} {pts[6][1]!r} {pts[7][0]!r} {pts[7][1]!r} Z"
            with open(self.svg, "w") as f:
                f.write(f'<svg xmlns="http://www.w3.org/2000/svg"><path d="{d}"/></svg>\n')
            P = [[M(x), -M(y)] for x, y in pts]
            self.edges = [[P[0], P[1], P[2], P[3]], [P[3], P[4]], [P[4], P[5], P[6], P[7]], [P[7], P[0]]]
        elif kind == "turned_cubic":
            pts = [[float(x * s / 60) for x in q] for seg in VASE for q in seg]
            self.svg = os.path.join(svg_dir(), f"vase_{s!r}.svg")
            f_ = lambda q: f"{q[0]!r} {q[1]!r}"
            d = f"M {f_(pts[0])} L {f_(pts[1])} C {f_(pts[2])} {f_(pts[3])} {f_(pts[4])} L {f_(pts[5])} C {f_(pts[6])} {f_(pts[7])} {f_(pts[8])} Z"
            with open(self.svg, "w") as f:
                f.write(f'<svg xmlns="http://www.w3.org/2000/svg"><path d="{d}"/></svg>\n')
            P = [[M(x), -M(y)] for x, y in pts]
            self.edges = [[P[0], P[1]], [P[1], P[2], P[3], P[4]], [P[4], P[5]], [P[5], P[6], P[7], P[8]], [P[8], P[0]]]
        elif kind == "twisted_ellipse":
            self.edges = []
            self.A = [[M(x * s) for x in row] for row in ELLIPSE_A]
            self.ec = [M(x * s) for x in ELLIPSE_C]
        else:
            pts = PROFILE if kind == "lathe" else L_SHAPE
            pts = [[M(x * s) for x in q] for q in pts]
            self.edges = [[pts[i], pts[(i + 1) % len(pts)]] for i in range(len(pts))]

    def body(self):
        s = self.s
        if self.kind == "glyph":
            return f"linear_extrude(height = {s!r}, center = true) text(\"e\", size = {s!r}, halign = \"center\", valign = \"center\");"
        if self.kind == "cubic":
            return f"linear_extrude(height = {s!r}, center = true) import(\"{self.svg}\");"
        if self.kind == "turned_cubic":
            return f"rotate_extrude() import(\"{self.svg}\");"
        pts = PROFILE if self.kind == "lathe" else L_SHAPE
        poly = "polygon([" + ", ".join(f"[{x * s!r}, {y * s!r}]" for x, y in pts) + "])"
        if self.kind == "twisted_ellipse":
            (a, b), (c, d) = [[x * s for x in row] for row in ELLIPSE_A]
            cx, cy = [x * s for x in ELLIPSE_C]
            poly = f"multmatrix([[{a!r}, {b!r}, 0, {cx!r}], [{c!r}, {d!r}, 0, {cy!r}], [0, 0, 1, 0], [0, 0, 0, 1]]) circle(r = 1)"
        if self.kind == "lathe":
            return f"rotate_extrude() {poly};"
        extra = {
            "prism": "",
            "tapered": f", scale = {TAPER!r}",
            "twisted": f", twist = {TWIST!r}, scale = [{TWIST_SCALE[0]!r}, {TWIST_SCALE[1]!r}]",
        }.get(self.kind, f", twist = {TWIST!r}, scale = [{TWIST_SCALE[0]!r}, {TWIST_SCALE[1]!r}]")
        return f"linear_extrude(height = {s!r}, center = true{extra}) {poly};"

    # The section at height z (fraction f from the bottom): the region's
    # point q for a plane point p.
    def frac(self, z):
        return (z + self.h) / (2 * self.h)

    def to_region(self, p):
        f = self.frac(p[2])
        if self.kind == "tapered":
            w = 1 + (M(TAPER) - 1) * f
            return [p[0] / w, p[1] / w] if w > 0 else None
        if self.kind in ("twisted", "twisted_ellipse"):
            sx, sy = 1 + (M(TWIST_SCALE[0]) - 1) * f, 1 + (M(TWIST_SCALE[1]) - 1) * f
            a = mp.pi * M(TWIST) / 180 * f
            u, v = p[0] / sx, p[1] / sy
            return [mp.cos(a) * u - mp.sin(a) * v, mp.sin(a) * u + mp.cos(a) * v]
        return [p[0], p[1]]

    def ellipse_form(self, q):
        """|A^-1 (q - c)|^2 - 1: negative inside the ellipse."""
        (a, b), (c, d) = self.A
        x, y = q[0] - self.ec[0], q[1] - self.ec[1]
        det = a * d - b * c
        u, v = (d * x - b * y) / det, (-c * x + a * y) / det
        return u * u + v * v - 1

    def inside2(self, q):
        """Even-odd: crossings of the line from q along +x."""
        if self.kind == "twisted_ellipse":
            return self.ellipse_form(q) <= 0
        inside = False
        for e in self.edges:
            if len(e) == 2:
                a, b = e
                if (a[1] > q[1]) != (b[1] > q[1]):
                    x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                    inside ^= x > q[0]
                continue
            if len(e) == 4:
                ky = power(e, 1)
                for u in cubic_roots([ky[3], ky[2], ky[1], ky[0] - q[1]]):
                    if 0 <= u < 1:
                        x = sum(power(e, 0)[j] * u**j for j in range(4))
                        if x > q[0] and abs(sum(j * ky[j] * u ** (j - 1) for j in range(1, 4))) > 0:
                            inside ^= True
                continue
            a, c, b = e
            # y(u) = q_y: (a - 2c + b) u^2 + 2 (c - a) u + a - q
            k2, k1, k0 = a[1] - 2 * c[1] + b[1], 2 * (c[1] - a[1]), a[1] - q[1]
            for u in real_roots([k2, k1, k0]):
                if 0 <= u < 1:
                    x = (1 - u) ** 2 * a[0] + 2 * u * (1 - u) * c[0] + u * u * b[0]
                    if x > q[0] and abs(2 * k2 * u + k1) > 0:
                        inside ^= True
        return inside

    def contains(self, p):
        if self.kind in ("lathe", "turned_cubic"):
            return self.inside2([mp.sqrt(p[0] ** 2 + p[1] ** 2), p[2]])
        if abs(p[2]) > self.h:
            return False
        q = self.to_region(p)
        return q is not None and self.inside2(q)

    def tagged(self, o, d):
        """Every boundary crossing (t, surface) of the local line."""
        out = []
        if self.kind in ("lathe", "turned_cubic"):
            for i, e_ in enumerate(self.edges):
                if len(e_) == 4:
                    # X(u)^2 = rho(t(u))^2 with t(u) = (Z(u) - o_z) / d_z: a
                    # sextic in u.
                    if d[2] == 0:
                        continue
                    kx, kz = power(e_, 0), power(e_, 1)
                    kt = [(kz[j] - (o[2] if j == 0 else 0)) / d[2] for j in range(4)]
                    mulp = lambda p_, q_: [sum(p_[i_] * q_[j - i_] for i_ in range(len(p_)) if 0 <= j - i_ < len(q_)) for j in range(len(p_) + len(q_) - 1)]
                    a2 = d[0] ** 2 + d[1] ** 2
                    b2 = 2 * (o[0] * d[0] + o[1] * d[1])
                    c2 = o[0] ** 2 + o[1] ** 2
                    x2, t2 = mulp(kx, kx), mulp(kt, kt)
                    g = [x2[j] - a2 * t2[j] - b2 * (kt[j] if j < 4 else 0) - (c2 if j == 0 else 0) for j in range(7)]
                    while g and g[-1] == 0:
                        g.pop()
                    rs = mp.polyroots(g[::-1], maxsteps=400, extraprec=400) if len(g) > 1 else []
                    for u in rs:
                        if abs(mp.im(u)) <= mp.mpf(10) ** -25 and -mp.mpf(10) ** -30 <= mp.re(u) <= 1 + mp.mpf(10) ** -30:
                            u = mp.re(u)
                            out.append((sum(kt[j] * u**j for j in range(4)), ("curve", i)))
                    continue
                a, b = e_
                e = [b[0] - a[0], b[1] - a[1]]
                # rho e_z = a_r e_z + (z - a_z) e_r, squared: a quadratic.
                L0, L1 = a[0] * e[1] + (o[2] - a[1]) * e[0], d[2] * e[0]
                A = (d[0] ** 2 + d[1] ** 2) * e[1] ** 2 - L1 * L1
                B = 2 * (o[0] * d[0] + o[1] * d[1]) * e[1] ** 2 - 2 * L0 * L1
                C = (o[0] ** 2 + o[1] ** 2) * e[1] ** 2 - L0 * L0
                if e[1] == 0:
                    if d[2] != 0:
                        t = (a[1] - o[2]) / d[2]
                        rho = mp.sqrt((o[0] + t * d[0]) ** 2 + (o[1] + t * d[1]) ** 2)
                        u = (rho - a[0]) / e[0]
                        if 0 <= u <= 1:
                            out.append((t, ("ring", i)))
                    continue
                for t in real_roots([A, B, C]):
                    if (L0 + L1 * t) * e[1] < 0:
                        continue
                    z = o[2] + t * d[2]
                    u = (z - a[1]) / e[1]
                    if 0 <= u <= 1:
                        out.append((t, ("cone", i)))
            return sorted(out, key=lambda x: x[0])
        # Caps.
        if d[2] != 0:
            for zc in (-self.h, self.h):
                t = (zc - o[2]) / d[2]
                p = [o[i] + t * d[i] for i in range(3)]
                q = self.to_region(p)
                if q is not None and self.inside2(q):
                    out.append((t, ("cap", 1 if zc > 0 else -1)))
            tlo, thi = sorted([(-self.h - o[2]) / d[2], (self.h - o[2]) / d[2]])
        else:
            if abs(o[2]) >= self.h:
                return []
            tlo, thi = -mp.inf, mp.inf
        for i, e in enumerate(self.edges):
            for t in self.side_roots(o, d, e, tlo, thi):
                out.append((t, ("side", i)))
        if self.kind == "twisted_ellipse":
            for t in self.sampled_roots(lambda t: self.ellipse_form(self.to_region([o[i] + t * d[i] for i in range(3)])), o, d, tlo, thi):
                out.append((t, ("side", -1)))
        return sorted(out, key=lambda x: x[0])

    def reach(self):
        """The farthest any point of the twisted extrusion gets from its
        axis: the section's farthest point, times the larger scale."""
        if self.kind == "twisted_ellipse":
            (a, b), (c, d) = self.A
            f = a * a + b * b + c * c + d * d
            smax = mp.sqrt((f + mp.sqrt(f * f - 4 * (a * d - b * c) ** 2)) / 2)
            rho = mp.sqrt(self.ec[0] ** 2 + self.ec[1] ** 2) + smax
        else:
            rho = max(mp.sqrt(e[0][0] ** 2 + e[0][1] ** 2) for e in self.edges)
        return rho * max(1, *[M(x) for x in TWIST_SCALE])

    def sampled_roots(self, g, o, d, tlo, thi):
        """The sign changes of g over [tlo, thi] where the line is within
        the extrusion's reach of its axis: sampled finely, then bisected."""
        r = self.reach()
        near = side_pieces(d[0] ** 2 + d[1] ** 2, o[0] * d[0] + o[1] * d[1], o[0] ** 2 + o[1] ** 2 - r * r)
        if not near:
            return []
        tlo, thi = max(tlo, near[0][0]), min(thi, near[0][1])
        if tlo >= thi:
            return []
        steps = 160
        ts = [tlo + (thi - tlo) * j / steps for j in range(steps + 1)]
        gs = [g(t) for t in ts]
        return [mp.findroot(g, (ts[j], ts[j + 1]), solver="anderson") for j in range(steps) if (gs[j] > 0) != (gs[j + 1] > 0)]

    def side_roots(self, o, d, e, tlo, thi):
        """Where the line meets the side over edge e, within the slab."""
        out = []
        if len(e) == 4:
            # cross(B(u) - o, d) = 0: a cubic in u.
            kx, ky = power(e, 0), power(e, 1)
            kx[0], ky[0] = kx[0] - o[0], ky[0] - o[1]
            for u in cubic_roots([kx[j] * d[1] - ky[j] * d[0] for j in (3, 2, 1, 0)]):
                if 0 <= u <= 1:
                    pt = [sum(k[j] * u**j for j in range(4)) for k in (power(e, 0), power(e, 1))]
                    t = ((pt[0] - o[0]) * d[0] + (pt[1] - o[1]) * d[1]) / (d[0] ** 2 + d[1] ** 2)
                    if tlo <= t <= thi:
                        out.append(t)
            return out
        if self.kind == "glyph" and len(e) == 3:
            a, c, b = e
            # cross(B(u) - o, d) = 0: a quadratic in u.
            k = [[a[i] - 2 * c[i] + b[i], 2 * (c[i] - a[i]), a[i] - o[i]] for i in range(2)]
            co = [k[0][j] * d[1] - k[1][j] * d[0] for j in range(3)]
            for u in real_roots(co):
                if 0 <= u <= 1:
                    pt = [(1 - u) ** 2 * a[i] + 2 * u * (1 - u) * c[i] + u * u * b[i] for i in range(2)]
                    dd = d[0] ** 2 + d[1] ** 2
                    t = ((pt[0] - o[0]) * d[0] + (pt[1] - o[1]) * d[1]) / dd
                    if tlo <= t <= thi:
                        out.append(t)
            return out
        a, b = e
        ed = [b[0] - a[0], b[1] - a[1]]
        if self.kind in ("prism", "glyph", "cubic", "tapered"):
            # cross(p_xy - w a, e) = 0 with w = 1 + (k - 1) f(z): linear in t.
            kk = (M(TAPER) - 1) / (2 * self.h) if self.kind == "tapered" else M(0)
            w0 = 1 + kk * (o[2] + self.h)
            f0 = cross2([o[0] - w0 * a[0], o[1] - w0 * a[1]], ed)
            f1 = cross2([d[0] - kk * d[2] * a[0], d[1] - kk * d[2] * a[1]], ed)
            if f1 == 0:
                return []
            t = -f0 / f1
            if not (tlo <= t <= thi):
                return []
            p = [o[i] + t * d[i] for i in range(3)]
            q = self.to_region(p)
            if q is None:
                return []
            u = ((q[0] - a[0]) * ed[0] + (q[1] - a[1]) * ed[1]) / (ed[0] ** 2 + ed[1] ** 2)
            return [t] if 0 <= u <= 1 else []
        # Twisted: n.q(t) - c changes sign; sampled finely, then bisected.
        n = [ed[1], -ed[0]]
        c = n[0] * a[0] + n[1] * a[1]

        def g(t):
            q = self.to_region([o[i] + t * d[i] for i in range(3)])
            return n[0] * q[0] + n[1] * q[1] - c

        for t in self.sampled_roots(g, o, d, tlo, thi):
            q = self.to_region([o[i] + t * d[i] for i in range(3)])
            u = ((q[0] - a[0]) * ed[0] + (q[1] - a[1]) * ed[1]) / (ed[0] ** 2 + ed[1] ** 2)
            if 0 <= u <= 1:
                out.append(t)
        return out

    def crossings(self, o, d):
        lo, ld = self.local(o, d)
        return [t for t, _ in self.tagged(lo, ld)]

    def grad(self, p, tag):
        """The gradient of a function zero on the surface `tag` at local p."""
        kind, i = tag
        if kind == "cap":
            return [M(0), M(0), M(i)]
        if i == -1:
            return [mp.diff(lambda x, y, z: self.ellipse_form(self.to_region([x, y, z])), (p[0], p[1], p[2]), tuple(int(j == k) for j in range(3))) for k in range(3)]
        e = self.edges[i]
        if kind == "curve":
            u = self.param(e, [mp.sqrt(p[0] ** 2 + p[1] ** 2), p[2]])
            tg = [sum(j * k[j] * u ** (j - 1) for j in range(1, 4)) for k in (power(e, 0), power(e, 1))]
            rho = mp.sqrt(p[0] ** 2 + p[1] ** 2)
            return [tg[1] * p[0] / rho, tg[1] * p[1] / rho, -tg[0]]
        if kind in ("cone", "ring"):
            a, b = e
            rho = mp.sqrt(p[0] ** 2 + p[1] ** 2)
            er, ez = b[0] - a[0], b[1] - a[1]
            return [ez * p[0] / rho, ez * p[1] / rho, -er]
        if len(e) == 4:
            u = self.param(e, [p[0], p[1]])
            tg = [sum(j * k[j] * u ** (j - 1) for j in range(1, 4)) for k in (power(e, 0), power(e, 1))]
            return [tg[1], -tg[0], M(0)]
        if self.kind == "glyph" and len(e) == 3:
            a, c, b = e
            q = [p[0], p[1]]
            u = self.param(e, q)
            tg = [2 * (1 - u) * (c[j] - a[j]) + 2 * u * (b[j] - c[j]) for j in range(2)]
            return [tg[1], -tg[0], M(0)]

        def F(x, y, z):
            q = self.to_region([x, y, z])
            a, b = e
            ed = [b[0] - a[0], b[1] - a[1]]
            return ed[1] * (q[0] - a[0]) - ed[0] * (q[1] - a[1])

        return [mp.diff(F, (p[0], p[1], p[2]), tuple(int(j == k) for j in range(3))) for k in range(3)]

    def param(self, e, q):
        if len(e) == 4:
            best = None
            for i in range(2):
                k = power(e, i)
                for u in cubic_roots([k[3], k[2], k[1], k[0] - q[i]]):
                    if -1e-20 <= u <= 1 + 1e-20:
                        pt = [sum(kk[j] * u**j for j in range(4)) for kk in (power(e, 0), power(e, 1))]
                        dist = (pt[0] - q[0]) ** 2 + (pt[1] - q[1]) ** 2
                        if best is None or dist < best[0]:
                            best = (dist, u)
            return best[1]
        a, c, b = e
        best = None
        for j in range(2):
            for u in real_roots([a[j] - 2 * c[j] + b[j], 2 * (c[j] - a[j]), a[j] - q[j]]):
                if -1e-20 <= u <= 1 + 1e-20:
                    pt = [(1 - u) ** 2 * a[k] + 2 * u * (1 - u) * c[k] + u * u * b[k] for k in range(2)]
                    dist = (pt[0] - q[0]) ** 2 + (pt[1] - q[1]) ** 2
                    if best is None or dist < best[0]:
                        best = (dist, u)
        return best[1]

    def normal(self, o, d, t):
        lo, ld = self.local(o, d)
        tag = min(self.tagged(lo, ld), key=lambda x: abs(x[0] - t))[1]
        p = [lo[i] + t * ld[i] for i in range(3)]
        g = self.grad(p, tag)
        ln = mp.sqrt(dot(g, g))
        g = [x / ln for x in g]
        eps = M(self.s) * mp.mpf(10) ** -20
        if self.contains([p[i] + eps * g[i] for i in range(3)]):
            g = [-x for x in g]
        # The curvature radius: a plane side none; a turned side its
        # distance from the axis (no more than its radii); a glyph's curve
        # |B'|^3 / |B' x B''|; a twisted side the rate its normal field
        # turns along the ray (half of it, for margin).
        kind, i = tag
        if kind == "cap" or self.kind in ("prism", "tapered") or self.kind in ("glyph", "cubic") and kind == "side" and len(self.edges[i]) == 2:
            rho = mp.inf
        elif self.kind == "cubic":
            e = self.edges[i]
            u = self.param(e, p)
            k = (power(e, 0), power(e, 1))
            b1 = [sum(j * kk[j] * u ** (j - 1) for j in range(1, 4)) for kk in k]
            b2 = [sum(j * (j - 1) * kk[j] * u ** (j - 2) for j in range(2, 4)) for kk in k]
            cr = abs(cross2(b1, b2))
            rho = mp.inf if cr == 0 else mp.sqrt(b1[0] ** 2 + b1[1] ** 2) ** 3 / cr
        elif kind in ("cone", "ring"):
            rho = mp.sqrt(p[0] ** 2 + p[1] ** 2)
        elif kind == "curve":
            e = self.edges[i]
            u = self.param(e, [mp.sqrt(p[0] ** 2 + p[1] ** 2), p[2]])
            k = (power(e, 0), power(e, 1))
            b1 = [sum(j * kk[j] * u ** (j - 1) for j in range(1, 4)) for kk in k]
            b2 = [sum(j * (j - 1) * kk[j] * u ** (j - 2) for j in range(2, 4)) for kk in k]
            cr = abs(cross2(b1, b2))
            rho = mp.sqrt(p[0] ** 2 + p[1] ** 2)
            if cr != 0:
                rho = min(rho, mp.sqrt(b1[0] ** 2 + b1[1] ** 2) ** 3 / cr)
        elif self.kind == "glyph":
            a, c, b = self.edges[i]
            u = self.param(self.edges[i], p)
            b1 = [2 * (1 - u) * (c[j] - a[j]) + 2 * u * (b[j] - c[j]) for j in range(2)]
            b2 = [2 * (a[j] - 2 * c[j] + b[j]) for j in range(2)]
            k = abs(cross2(b1, b2))
            rho = mp.inf if k == 0 else mp.sqrt(b1[0] ** 2 + b1[1] ** 2) ** 3 / k
        else:
            def nf(tt):
                q = [lo[j] + tt * ld[j] for j in range(3)]
                gg = self.grad(q, tag)
                l2 = mp.sqrt(dot(gg, gg))
                return [x / l2 for x in gg]

            dn = [mp.diff(lambda tt, j=j: nf(tt)[j], t) for j in range(3)]
            rate = mp.sqrt(dot(dn, dn)) / mp.sqrt(dot(ld, ld))
            rho = mp.inf if rate == 0 else 1 / (2 * rate)
        w = apply(transpose(self.inv), g)
        ln = mp.sqrt(dot(w, w))
        return [x / ln for x in w], rho


# The offset glyph: the glyph's outline grown by this much of its size.
OFFSET_R = 0.04


class OffsetGlyph(Extruded):
    """The glyph's prism grown by OFFSET_R of its size (`offset(r)` of the
    text): the points within r of the region. Its boundary lies on the
    curves the edges' points trace at distance r along their normals and
    on the circles of radius r about their ends; along a line, the places
    it meets those (offset points B(u) + s r nu(u) on the line: u a root of
    (d x (B - o))^2 |B'|^2 - r^2 (d . B')^2, at 50 digits) are candidates,
    and the boundary is where the side changes between them (inside the
    region, or within r of an edge: the nearest point by the roots of
    (B - q) . B' = 0)."""

    def __init__(self, kind, c, s, pose="plain"):
        super().__init__("glyph", c, s, pose)
        self.kind = kind
        self.r_f = OFFSET_R * s
        self.r = M(self.r_f)
        # Each edge's control box grown by a little more than r (floats:
        # a filter only).
        self.boxes = []
        for e in self.edges:
            xs, ys = [float(q[0]) for q in e], [float(q[1]) for q in e]
            g = self.r_f * 1.01 + 1e-9 * s
            self.boxes.append((min(xs) - g, min(ys) - g, max(xs) + g, max(ys) + g))

    def body(self):
        if getattr(self, "r_f", None) is None:
            return super().body()
        s = self.s
        return f"linear_extrude(height = {s!r}, center = true) offset(r = {self.r_f!r}) text(\"e\", size = {s!r}, halign = \"center\", valign = \"center\");"

    def dist2(self, e, q):
        """(squared distance from q to edge e, its nearest parameter)."""
        if len(e) == 2:
            a, b = e
            ed = [b[0] - a[0], b[1] - a[1]]
            u = ((q[0] - a[0]) * ed[0] + (q[1] - a[1]) * ed[1]) / (ed[0] ** 2 + ed[1] ** 2)
            u = min(M(1), max(M(0), u))
            return (a[0] + u * ed[0] - q[0]) ** 2 + (a[1] + u * ed[1] - q[1]) ** 2, u
        a, c, b = e
        k0 = [a[i] - q[i] for i in range(2)]
        k1 = [2 * (c[i] - a[i]) for i in range(2)]
        k2 = [a[i] - 2 * c[i] + b[i] for i in range(2)]
        d2 = lambda x, y: x[0] * y[0] + x[1] * y[1]
        best = None
        for u in [M(0), M(1)] + [u for u in cubic_roots([2 * d2(k2, k2), 3 * d2(k1, k2), d2(k1, k1) + 2 * d2(k0, k2), d2(k0, k1)]) if 0 < u < 1]:
            v = (k0[0] + k1[0] * u + k2[0] * u * u) ** 2 + (k0[1] + k1[1] * u + k2[1] * u * u) ** 2
            if best is None or v < best[0]:
                best = (v, u)
        return best

    def near(self, q):
        return [i for i, (x0, y0, x1, y1) in enumerate(self.boxes) if x0 <= q[0] <= x1 and y0 <= q[1] <= y1]

    def inside_off(self, q):
        if self.inside2(q):
            return True
        r2 = self.r * self.r
        return any(self.dist2(self.edges[i], q)[0] <= r2 for i in self.near([float(q[0]), float(q[1])]))

    def contains(self, p):
        return abs(p[2]) <= self.h and self.inside_off([p[0], p[1]])

    def side_changes(self, o, d):
        """[(t, tag)] where the line o + t d (2-D) crosses the boundary."""
        dd = d[0] ** 2 + d[1] ** 2
        if dd == 0:
            return []
        r = self.r
        nl = [-d[1], d[0]]
        on = lambda x: nl[0] * (x[0] - o[0]) + nl[1] * (x[1] - o[1])
        tpar = lambda x: ((x[0] - o[0]) * d[0] + (x[1] - o[1]) * d[1]) / dd
        cands = []
        nlf = [float(x) for x in nl]
        ln = math.hypot(*nlf)
        of = [float(x) for x in o]
        for i, e in enumerate(self.edges):
            x0, y0, x1, y1 = self.boxes[i]
            vals = [nlf[0] * (x - of[0]) + nlf[1] * (y - of[1]) for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
            if all(v > 1e-9 * ln * self.s for v in vals) or all(v < -1e-9 * ln * self.s for v in vals):
                continue
            a = e[0]
            # The circle about the edge's start.
            for t in quadratic(dd, (o[0] - a[0]) * d[0] + (o[1] - a[1]) * d[1], (o[0] - a[0]) ** 2 + (o[1] - a[1]) ** 2 - r * r):
                cands.append((t, ("disc", i)))
            if len(e) == 2:
                b = e[1]
                ed = [b[0] - a[0], b[1] - a[1]]
                le = mp.sqrt(ed[0] ** 2 + ed[1] ** 2)
                nu = [-ed[1] / le, ed[0] / le]
                for sg in (1, -1):
                    p0 = [a[j] + sg * r * nu[j] for j in range(2)]
                    p1 = [b[j] + sg * r * nu[j] for j in range(2)]
                    s0, s1 = on(p0), on(p1)
                    if s0 != s1 and (s0 <= 0) != (s1 <= 0):
                        u = s0 / (s0 - s1)
                        cands.append((tpar([p0[j] + u * (p1[j] - p0[j]) for j in range(2)]), ("band", i, sg, u)))
                continue
            a, c, b = e
            k = [[a[j] - o[j], 2 * (c[j] - a[j]), a[j] - 2 * c[j] + b[j]] for j in range(2)]
            X = [d[0] * k[1][j] - d[1] * k[0][j] for j in range(3)]
            bx, by = [k[0][1], 2 * k[0][2]], [k[1][1], 2 * k[1][2]]
            bb = [bx[0] ** 2 + by[0] ** 2, 2 * (bx[0] * bx[1] + by[0] * by[1]), bx[1] ** 2 + by[1] ** 2]
            D = [d[0] * bx[0] + d[1] * by[0], d[0] * bx[1] + d[1] * by[1]]
            mulp = lambda p_, q_: [sum(p_[i_] * q_[j - i_] for i_ in range(len(p_)) if 0 <= j - i_ < len(q_)) for j in range(len(p_) + len(q_) - 1)]
            lhs, rhs = mulp(mulp(X, X), bb), mulp(D, D)
            g = [lhs[j] - (r * r * rhs[j] if j < len(rhs) else 0) for j in range(len(lhs))]
            while g and g[-1] == 0:
                g.pop()
            if len(g) < 2:
                continue
            for u in mp.polyroots(g[::-1], maxsteps=400, extraprec=400):
                if abs(mp.im(u)) > mp.mpf(10) ** -25 or not (0 < mp.re(u) < 1):
                    continue
                u = mp.re(u)
                B = [a[j] * (1 - u) ** 2 + 2 * c[j] * u * (1 - u) + b[j] * u * u for j in range(2)]
                tg = [bx[0] + bx[1] * u, by[0] + by[1] * u]
                lt = mp.sqrt(tg[0] ** 2 + tg[1] ** 2)
                for sg in (1, -1):
                    x = [B[0] - sg * r * tg[1] / lt, B[1] + sg * r * tg[0] / lt]
                    if abs(on(x)) <= mp.mpf(10) ** -30 * (1 + dd) * (abs(self.s) + abs(o[0]) + abs(o[1])):
                        cands.append((tpar(x), ("band", i, sg, u)))
        cands.sort(key=lambda x: x[0])
        out, inside = [], False
        for j, (t, tag) in enumerate(cands):
            now = j + 1 < len(cands) and self.inside_off([o[0] + (t + cands[j + 1][0]) / 2 * d[0], o[1] + (t + cands[j + 1][0]) / 2 * d[1]])
            if now != inside:
                out.append((t, tag))
                inside = now
        return out

    def tagged(self, o, d):
        out = []
        if d[2] != 0:
            for zc in (-self.h, self.h):
                t = (zc - o[2]) / d[2]
                if self.inside_off([o[0] + t * d[0], o[1] + t * d[1]]):
                    out.append((t, ("cap", 1 if zc > 0 else -1)))
            tlo, thi = sorted([(-self.h - o[2]) / d[2], (self.h - o[2]) / d[2]])
        else:
            if abs(o[2]) >= self.h:
                return []
            tlo, thi = -mp.inf, mp.inf
        out += [(t, tag) for t, tag in self.side_changes(o, d) if tlo <= t <= thi]
        return sorted(out, key=lambda x: x[0])

    def normal(self, o, d, t):
        lo, ld = self.local(o, d)
        tag = min(self.tagged(lo, ld), key=lambda x: abs(x[0] - t))[1]
        p = [lo[i] + t * ld[i] for i in range(3)]
        rho = mp.inf
        if tag[0] == "cap":
            g = [M(0), M(0), M(tag[1])]
        elif tag[0] == "disc":
            v = self.edges[tag[1]][0]
            g, rho = [p[0] - v[0], p[1] - v[1], M(0)], self.r
        else:
            _, i, sg, u = tag
            e = self.edges[i]
            if len(e) == 2:
                B = [e[0][j] + u * (e[1][j] - e[0][j]) for j in range(2)]
            else:
                a, c, b = e
                B = [a[j] * (1 - u) ** 2 + 2 * c[j] * u * (1 - u) + b[j] * u * u for j in range(2)]
                b1 = [2 * (1 - u) * (c[j] - a[j]) + 2 * u * (b[j] - c[j]) for j in range(2)]
                b2 = [2 * (a[j] - 2 * c[j] + b[j]) for j in range(2)]
                kap = cross2(b1, b2) / mp.sqrt(b1[0] ** 2 + b1[1] ** 2) ** 3
                # The offset curve's radius: the centre of curvature lies
                # 1/kappa along the left normal, the point r * sg along it.
                rho = mp.inf if kap == 0 else abs(1 / kap - sg * self.r)
            g = [p[0] - B[0], p[1] - B[1], M(0)]
        ln = mp.sqrt(dot(g, g))
        g = [x / ln for x in g]
        eps = M(self.s) * mp.mpf(10) ** -20
        if self.contains([p[i] + eps * g[i] for i in range(3)]):
            g = [-x for x in g]
        w = apply(transpose(self.inv), g)
        ln = mp.sqrt(dot(w, w))
        return [x / ln for x in w], rho


def power(e, i):
    """Coordinate i of the cubic Bézier edge e in the power basis: k0 + k1
    u + k2 u^2 + k3 u^3."""
    p0, p1, p2, p3 = (q[i] for q in e)
    return [p0, 3 * (p1 - p0), 3 * (p0 - 2 * p1 + p2), p3 - 3 * p2 + 3 * p1 - p0]


def cubic_roots(c):
    """The real roots of c[0] u^3 + c[1] u^2 + c[2] u + c[3] (lower degrees
    when the leading coefficients vanish), polished at 50 digits."""
    while c and c[0] == 0:
        c = c[1:]
    if len(c) < 2:
        return []
    if len(c) == 3:
        return real_roots(c)
    if len(c) == 2:
        return [-c[1] / c[0]]
    rs = mp.polyroots(c, maxsteps=200, extraprec=200)
    return sorted(mp.re(r) for r in rs if abs(mp.im(r)) <= mp.mpf(10) ** -30 * (1 + abs(r)))


def torus_crossings(o, d, R, r):
    """Sorted exact t of every crossing of the line o + t d with the torus
    about the z axis of major radius R and tube radius r."""
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
    return sorted(mp.re(x) for x in roots if abs(mp.im(x)) < mp.mpf(10) ** -30)


def real_roots(c):
    """Real roots of c[0] u^2 + c[1] u + c[2] (any of them zero)."""
    a, b, k = c
    if a == 0:
        return [] if b == 0 else [-k / b]
    disc = b * b - 4 * a * k
    if disc < 0:
        return []
    q = mp.sqrt(disc)
    return sorted([(-b - q) / (2 * a), (-b + q) / (2 * a)])


def extrusion_rays(p, n, rng):
    """Random rays at random inner points, rays from inside, and rays
    along a prism's vertical edge 1e-9 of the size inside its corner, or
    grazing a turned profile's outer cylinder."""
    c, s = p.c, p.s
    out = []

    def at(*rel):
        return [c[i] + rel[i] * s for i in range(3)]

    inner = []
    while len(inner) < n:
        q = [rng.uniform(-0.5, 0.5) for _ in range(3)]
        if p.contains([M(x * s) for x in q]):
            inner.append(q)
    for q in inner:
        u = [rng.gauss(0, 1) for _ in range(3)]
        nu = sum(x * x for x in u) ** 0.5
        o = at(*(3 * x / nu for x in u))
        target = at(*q)
        out.append(("random", o, unit([target[i] - o[i] for i in range(3)])))
        out.append(("inside", at(*q), unit(u)))
    ulp = math.ulp(max(abs(x) for x in c) or 1.0)
    slim = max(SLIM, 8 * ulp / s)
    for j in range(max(2, n // 4)):
        if p.kind == "lathe":
            a = 2 * math.pi * j / n
            o = at(-3.0, 0.5 * (1 - slim), -0.25 + 0.05 * math.sin(a))
            out.append(("grazing", o, [1.0, 0.0, 0.0]))
        elif p.kind not in ("glyph", "cubic", "offset_glyph"):
            e = -0.5 + slim
            out.append(("edge", at(e, e, -3.0), [0.0, 0.0, 1.0]))
    return out


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
# hull() and minkowski(): closed forms of a tapered capsule, a rounded box
# and the hull of points
# --------------------------------------------------------------------------

CONVEXES = ["hull_spheres", "hull_spheres_support", "rounded_box", "hull_points", "lofted_plate", "chamfered_plate"]
# The tapered capsule twice: as written (csgrt's exact pieces, balls and the
# tangent frustum) and with a small cube inside it among the hull's parts
# (the same set, which only the support function's path takes: GJK and
# Newton's proof).
SPHERE_HULLS = ("hull_spheres", "hull_spheres_support")
# The hull of two balls on the z axis: centres and radii, times the size.
CAPSULE = ((-0.3, 0.35), (0.4, 0.15))
# The rounded box: a centred box's sides and the ball's radius, times the size.
BOX_SIDES, BOX_R = (0.6, 0.4, 0.3), 0.15
# The lofted plate: the hull of four cylinders at (+-A, +-B), the pair at
# y = -B from z0 up by HC, the pair at y = B from z1 up by HC, radius R;
# times the size.
LOFT_A, LOFT_B, LOFT_R, LOFT_HC, LOFT_Z0, LOFT_Z1 = 0.35, 0.25, 0.12, 0.1, -0.3, 0.05
# The chamfered plate: a rounded rectangle (half sides A1, B1, radius R1)
# from Z0 to Z1 under a smaller one (A2, B2, R2) from Z2 to Z3, hulled;
# times the size.
CHAMFER = dict(a1=0.35, b1=0.25, r1=0.12, z0=-0.3, z1=0.05, a2=0.2, b2=0.12, r2=0.05, z2=0.2, z3=0.24)
# The hull of points: twelve points in general position, as three
# tetrahedra, times the size.
POINTS = [
    (-0.41, -0.33, -0.28), (0.37, -0.29, -0.35), (0.05, 0.44, -0.31), (-0.02, 0.03, 0.47),
    (0.45, 0.21, 0.08), (-0.46, 0.18, 0.13), (0.12, -0.47, 0.19), (0.21, 0.36, 0.33),
    (-0.23, -0.12, -0.49), (0.31, -0.05, 0.42), (-0.35, 0.39, -0.17), (0.02, -0.21, -0.11),
]


class Convexed(Prim):
    """hull() of two balls (a tapered capsule), minkowski() of a box and a
    ball (a rounded box), hull() of twelve points, or hull() of four
    cylinders, a raised pair and a low one (a lofted plate), of size s
    centred at c. The line meets a convex set in one interval: the union of
    the intervals of convex pieces that cover it (the balls and the frustum
    tangent to both; 3 boxes, 12 cylinders and 8 balls; see loft_pieces),
    or the facets' half-spaces."""

    def __init__(self, kind, c, s, pose="plain"):
        super().__init__(kind, c, s, pose)
        S = M(s)
        if kind in SPHERE_HULLS:
            (z1, r1), (z2, r2) = [(M(float(z * s)), M(float(r * s))) for z, r in CAPSULE]
            self.balls = [([M(0), M(0), z1], r1), ([M(0), M(0), z2], r2)]
            sin_a = (r1 - r2) / (z2 - z1)
            cos_a = mp.sqrt(1 - sin_a**2)
            # The frustum between the tangency circles.
            self.z1t, self.z2t = z1 + r1 * sin_a, z2 + r2 * sin_a
            self.rho1, self.k = r1 * cos_a, -sin_a / cos_a
        elif kind == "rounded_box":
            self.half = [M(float(x * s)) / 2 for x in BOX_SIDES]
            self.r = M(float(BOX_R * s))
        elif kind == "lofted_plate":
            self.loft = [M(float(x * s)) for x in (LOFT_A, LOFT_B, LOFT_R, LOFT_HC, LOFT_Z0, LOFT_Z1)]
        elif kind == "chamfered_plate":
            self.ch = {k: M(float(v * s)) for k, v in CHAMFER.items()}
        else:
            self.pts = [[M(float(x * s)) for x in q] for q in POINTS]
            self.planes = hull_planes(self.pts)
        self.S = S

    def body(self):
        s = self.s
        f = lambda x: repr(float(x * s))
        if self.kind in SPHERE_HULLS:
            balls = " ".join(f"translate([0, 0, {f(z)}]) sphere(r = {f(r)});" for z, r in CAPSULE)
            if self.kind == "hull_spheres_support":
                balls += f" translate([0, 0, {f(0.05)}]) cube({f(0.01)}, center = true);"
            return f"hull() {{ {balls} }}"
        if self.kind == "rounded_box":
            sides = ", ".join(f(x) for x in BOX_SIDES)
            return f"minkowski() {{ cube([{sides}], center = true); sphere(r = {f(BOX_R)}); }}"
        if self.kind == "lofted_plate":
            cyls = " ".join(
                f"translate([{f(sx * LOFT_A)}, {f(sy * LOFT_B)}, {f(z)}]) cylinder(r = {f(LOFT_R)}, h = {f(LOFT_HC)});"
                for sx in (-1, 1)
                for sy, z in ((-1, LOFT_Z0), (1, LOFT_Z1))
            )
            return f"hull() {{ {cyls} }}"
        if self.kind == "chamfered_plate":
            c = CHAMFER

            def plate(a, b, r, z, h):
                sq = f"square([{f(2 * a)}, {f(2 * b)}], center = true)"
                return f"translate([0, 0, {f(z)}]) linear_extrude(height = {f(h)}) offset(r = {f(r)}) {sq};"

            low = plate(c["a1"], c["b1"], c["r1"], c["z0"], c["z1"] - c["z0"])
            high = plate(c["a2"], c["b2"], c["r2"], c["z2"], c["z3"] - c["z2"])
            return f"hull() {{ {low} {high} }}"
        tets = []
        for j in range(0, len(POINTS), 4):
            p = [[float(x * s) for x in q] for q in POINTS[j : j + 4]]
            pts = ", ".join("[" + ", ".join(repr(x) for x in q) + "]" for q in p)
            faces = ", ".join(str(fc) for fc in tetra_faces([[M(x) for x in q] for q in p]))
            tets.append(f"polyhedron(points = [{pts}], faces = [{faces}]);")
        return "hull() { " + " ".join(tets) + " }"

    def intervals(self, o, d):
        """The intervals of t in each convex piece (local ray)."""
        out = []
        if self.kind in SPHERE_HULLS:
            for cen, r in self.balls:
                rel = [o[i] - cen[i] for i in range(3)]
                q = quadratic(dot(d, d), dot(rel, d), dot(rel, rel) - r * r)
                if q:
                    out.append(tuple(q))
            # x^2 + y^2 = (rho1 + k (z - z1t))^2 for z1t <= z <= z2t
            rz0 = self.rho1 + self.k * (o[2] - self.z1t)
            a = d[0] ** 2 + d[1] ** 2 - self.k**2 * d[2] ** 2
            b = o[0] * d[0] + o[1] * d[1] - self.k * d[2] * rz0
            c = o[0] ** 2 + o[1] ** 2 - rz0 * rz0
            out += clipped(pieces(a, b, c), slab(o[2], d[2], self.z1t, self.z2t))
        elif self.kind == "rounded_box":
            h, r = self.half, self.r
            for i in range(3):
                grown = [h[j] + (r if j == i else 0) for j in range(3)]
                box = clip_box(o, d, [-x for x in grown], grown)
                if box:
                    out.append(box)
                j, k = (i + 1) % 3, (i + 2) % 3
                for sj in (-1, 1):
                    for sk in (-1, 1):
                        cj, ck = sj * h[j], sk * h[k]
                        a = d[j] ** 2 + d[k] ** 2
                        b = (o[j] - cj) * d[j] + (o[k] - ck) * d[k]
                        c = (o[j] - cj) ** 2 + (o[k] - ck) ** 2 - r * r
                        out += clipped(pieces(a, b, c), slab(o[i], d[i], -h[i], h[i]))
            for sx in (-1, 1):
                for sy in (-1, 1):
                    for sz in (-1, 1):
                        rel = [o[0] - sx * h[0], o[1] - sy * h[1], o[2] - sz * h[2]]
                        q = quadratic(dot(d, d), dot(rel, d), dot(rel, rel) - r * r)
                        if q:
                            out.append(tuple(q))
        elif self.kind == "lofted_plate":
            out += [iv for iv, _ in loft_pieces(self.loft, o, d)]
        elif self.kind == "chamfered_plate":
            out += chamfer_pieces(self.ch, o, d)
        else:
            lo, hi = -mp.inf, mp.inf
            for n, h in self.planes:
                nd, no = dot(n, d), dot(n, o)
                if nd == 0:
                    if no > h:
                        return []
                    continue
                t = (h - no) / nd
                lo, hi = (max(lo, t), hi) if nd < 0 else (lo, min(hi, t))
            if lo < hi:
                out.append((lo, hi))
        return out

    def crossings(self, o, d):
        o, d = self.local(o, d)
        iv = [x for x in self.intervals(o, d) if x[0] < x[1]]
        if not iv:
            return []
        return [min(x[0] for x in iv), max(x[1] for x in iv)]

    def normal(self, o, d, t):
        lo, ld = self.local(o, d)
        p = [lo[i] + t * ld[i] for i in range(3)]
        if self.kind in SPHERE_HULLS:
            if p[2] <= self.z1t or p[2] >= self.z2t:
                cen, r = self.balls[0] if p[2] <= self.z1t else self.balls[1]
                n, rho = [p[i] - cen[i] for i in range(3)], r
            else:
                rxy = mp.sqrt(p[0] ** 2 + p[1] ** 2)
                n = [p[0] / rxy, p[1] / rxy, -self.k]
                rho = (self.rho1 + self.k * (p[2] - self.z1t)) * mp.sqrt(1 + self.k**2)
        elif self.kind == "rounded_box":
            h = self.half
            q = [max(-h[i], min(h[i], p[i])) for i in range(3)]
            n = [p[i] - q[i] for i in range(3)]
            # Off a face by the rounding error of p: the face's normal.
            big = max(abs(x) for x in n)
            curved = sum(1 for x in n if abs(x) > big * mp.mpf(10) ** -20) > 1
            rho = self.r if curved else mp.inf
        elif self.kind == "lofted_plate":
            n, rho = loft_normal(self.loft, p)
        elif self.kind == "chamfered_plate":
            n, rho = chamfer_normal(self.ch, p)
        else:
            n, _ = min(self.planes, key=lambda nh: abs(dot(nh[0], p) - nh[1]))
            rho = mp.inf
        w = apply(transpose(self.inv), n)
        ln = mp.sqrt(dot(w, w))
        return [x / ln for x in w], rho


def loft_edges(loft):
    """The lofted plate's section through x = 0 (a parallelogram in y, z:
    the hull of the cylinders' axes seen along x) as its four edges, each
    (start, end) in (y, z), counter-clockwise from the low pair's bottom."""
    _, b, _, hc, z0, z1 = loft
    v = [(-b, z0 + hc), (-b, z0), (b, z1), (b, z1 + hc)]
    return [(v[i], v[(i + 1) % 4]) for i in range(4)]


def loft_pieces(loft, o, d):
    """The lofted plate as convex pieces, each (interval of t, name): every
    horizontal section is the section of the axes' hull, a rectangle
    [-A, A] x [ylo(z), yhi(z)], grown by R: the rectangle grown along x,
    the rectangle grown along y, and the discs about its four corners,
    which lie on the edges of the parallelogram at x = +-A (each corner's
    discs over its edge's heights: a cylinder of circular horizontal
    sections swept along the edge)."""
    a, b, r, hc, z0, z1 = loft
    k = (z1 - z0) / (2 * b)
    out = []

    def halfspaces(planes):
        lo, hi = -mp.inf, mp.inf
        for n, h in planes:
            nd, no = dot(n, d), dot(n, o)
            if nd == 0:
                if no > h:
                    return None
                continue
            t = (h - no) / nd
            lo, hi = (max(lo, t), hi) if nd < 0 else (lo, min(hi, t))
        return (lo, hi) if lo < hi else None

    # The parallelogram: -B <= y <= B, z0 + k (y + B) <= z <= z0 + HC + k (y + B),
    # as k y - z <= -z0 - k B and z - k y <= z0 + HC + k B; along y grown by
    # R (a shift of each bounding line by R along y).
    for grow_x, grow_y in ((r, 0), (0, r)):
        planes = [
            ([M(1), M(0), M(0)], a + grow_x),
            ([M(-1), M(0), M(0)], a + grow_x),
            ([M(0), M(1), M(0)], b + grow_y),
            ([M(0), M(-1), M(0)], b + grow_y),
            ([M(0), k, M(-1)], -z0 - k * b + k * grow_y),
            ([M(0), -k, M(1)], z0 + hc + k * b + k * grow_y),
            ([M(0), M(0), M(1)], z1 + hc),
            ([M(0), M(0), M(-1)], -z0),
        ]
        iv = halfspaces(planes)
        if iv:
            out.append((iv, "grown"))
    for sx in (-1, 1):
        for (ya, za), (yb, zb) in loft_edges(loft):
            x = sx * a
            # The offset across at height o_z + t d_z from the edge's point there.
            sy = (yb - ya) / (zb - za)
            g0, g1 = o[0] - x, d[0]
            e0 = o[1] - ya - (o[2] - za) * sy
            e1 = d[1] - d[2] * sy
            qa, qb, qc = g1 * g1 + e1 * e1, g0 * g1 + e0 * e1, g0 * g0 + e0 * e0 - r * r
            for iv in clipped(pieces(qa, qb, qc), slab(o[2], d[2], min(za, zb), max(za, zb))):
                out.append((iv, "swept"))
    return out


def loft_normal(loft, p):
    """The exact outward normal of the lofted plate at its boundary point p
    and the smallest radius of curvature there: from p's section, the
    point q of the section's rectangle nearest p, the offset w = p - q
    (length R on the side): along x or y off an edge of the rectangle, the
    normal of the face of the axes' hull that makes that edge; off a
    corner, across the swept cylinder: w turned a quarter about z, crossed
    with the edge's direction s (its radius of curvature at least R |s_z| /
    |s|, the normal turning |s| / |s_z| times as fast as w). On a cap, +-z."""
    a, b, r, hc, z0, z1 = loft
    k = (z1 - z0) / (2 * b)
    tiny = mp.mpf(10) ** -25 * (abs(a) + abs(b))
    if abs(p[2] - (z1 + hc)) <= tiny or abs(p[2] - z0) <= tiny:
        return [M(0), M(0), M(1) if p[2] > 0 else M(-1)], mp.inf
    # The rectangle's y-range at p's height, and which face makes each end.
    lo_top = (p[2] - z0 - hc) / k - b  # the top slanted face bounds y below
    hi_bot = (p[2] - z0) / k - b  # the bottom slanted face bounds y above
    ylo, nlo, elo = (-b, [M(0), M(-1), M(0)], 0) if -b >= lo_top else (lo_top, [M(0), -k, M(1)], 3)
    yhi, nhi, ehi = (b, [M(0), M(1), M(0)], 2) if b <= hi_bot else (hi_bot, [M(0), k, M(-1)], 1)
    qx = max(-a, min(a, p[0]))
    qy = max(ylo, min(yhi, p[1]))
    w = [p[0] - qx, p[1] - qy]
    corner = abs(w[0]) > tiny and abs(w[1]) > tiny
    if not corner:
        if abs(w[0]) > tiny:
            return [M(1) if w[0] > 0 else M(-1), M(0), M(0)], mp.inf
        return (nhi if w[1] > 0 else nlo), mp.inf
    (ya, za), (yb, zb) = loft_edges(loft)[ehi if w[1] > 0 else elo]
    s = [M(0), yb - ya, zb - za]
    perp = [-w[1], w[0], M(0)]
    n = cross3(perp, s)
    if n[0] * w[0] + n[1] * w[1] < 0:
        n = [-x for x in n]
    return n, r * abs(s[2]) / mp.sqrt(dot(s, s))


def chamfer_section(ch, z):
    """The chamfered plate's section at height z as a rounded rectangle
    (half sides, radius) and their rates along z; None off its heights.
    The smaller plate lies inside the larger one's outline, so the hull is
    the lower plate and, from its top (Z1) to the upper plate's top (Z3),
    the hull of those two flat rounded rectangles, whose section at a
    fraction l of the way is (1 - l) times the one plus l times the other:
    the half sides and the radius interpolated (an offset of a rectangle is
    the rectangle plus a disc, and Minkowski combinations add)."""
    if z < ch["z0"] or z > ch["z3"]:
        return None
    if z <= ch["z1"]:
        return (ch["a1"], ch["b1"], ch["r1"]), (M(0), M(0), M(0))
    span = ch["z3"] - ch["z1"]
    l = (z - ch["z1"]) / span
    rates = tuple((ch[k + "2"] - ch[k + "1"]) / span for k in ("a", "b", "r"))
    return tuple(ch[k + "1"] + (ch[k + "2"] - ch[k + "1"]) * l for k in ("a", "b", "r")), rates


def chamfer_pieces(ch, o, d):
    """The intervals of t in the chamfered plate's convex pieces: over each
    of its two height ranges, the rounded rectangle's two crossed boxes
    (their sides moving linearly with z: half-spaces) and its four corner
    discs (centres and radius linear in z: a cylinder below, oblique cones
    above, each a quadratic in t)."""
    out = []
    for lo, hi in ((ch["z0"], ch["z1"]), (ch["z1"], ch["z3"])):
        zs = slab(o[2], d[2], lo, hi)
        if zs is None:
            continue
        (a, b, r), (da, db, dr) = chamfer_section(ch, (lo + hi) / 2)
        a, b, r = a - da * (hi - lo) / 2, b - db * (hi - lo) / 2, r - dr * (hi - lo) / 2
        # At height z: a + da (z - lo), and so on; along the line z = o_z + t d_z.
        at = lambda v0, rate: (v0 + rate * (o[2] - lo), rate * d[2])
        for wx, wy in ((1, 0), (0, 1)):
            hx0, hx1 = at(a + wx * r, da + wx * dr)
            hy0, hy1 = at(b + wy * r, db + wy * dr)
            iv = zs
            for g0, g1, h0, h1 in ((o[0], d[0], hx0, hx1), (o[1], d[1], hy0, hy1)):
                # -h(t) <= g0 + g1 t <= h(t)
                for sign in (1, -1):
                    k0, k1 = sign * g0 - h0, sign * g1 - h1  # k0 + k1 t <= 0
                    if k1 == 0:
                        if k0 > 0:
                            iv = None
                            break
                        continue
                    t = -k0 / k1
                    iv = (iv[0], min(iv[1], t)) if k1 > 0 else (max(iv[0], t), iv[1])
                if iv is None or iv[0] >= iv[1]:
                    iv = None
                    break
            if iv:
                out.append(iv)
        for sx in (-1, 1):
            for sy in (-1, 1):
                cx0, cx1 = at(sx * a, sx * da)
                cy0, cy1 = at(sy * b, sy * db)
                r0, r1 = at(r, dr)
                gx0, gx1 = o[0] - cx0, d[0] - cx1
                gy0, gy1 = o[1] - cy0, d[1] - cy1
                qa = gx1 * gx1 + gy1 * gy1 - r1 * r1
                qb = gx0 * gx1 + gy0 * gy1 - r0 * r1
                qc = gx0 * gx0 + gy0 * gy0 - r0 * r0
                out += clipped(side_pieces(qa, qb, qc), zs)
    return out


def chamfer_normal(ch, p):
    """The exact outward normal of the chamfered plate at boundary point p,
    and the smallest radius of curvature there: on a cap, +-z; else, with
    F = (distance across from the section's inner rectangle) - radius, its
    gradient: on a side, (+-1, 0, -(half side + radius)') or its y
    counterpart; off a corner, w (the unit offset from the corner's
    centre) and -(w . centre' + radius') along z — constant along a
    ruling, and turning at most sqrt(1 + |centre'|^2) times as fast as w
    across: a radius of curvature at least the section's radius over
    that."""
    tiny = mp.mpf(10) ** -25 * ch["a1"]
    if abs(p[2] - ch["z3"]) <= tiny:
        return [M(0), M(0), M(1)], mp.inf
    if abs(p[2] - ch["z0"]) <= tiny:
        return [M(0), M(0), M(-1)], mp.inf
    (a, b, r), (da, db, dr) = chamfer_section(ch, p[2])
    qx, qy = max(-a, min(a, p[0])), max(-b, min(b, p[1]))
    w = [p[0] - qx, p[1] - qy]
    if abs(w[0]) > tiny and abs(w[1]) > tiny:
        lw = mp.sqrt(w[0] ** 2 + w[1] ** 2)
        u = [w[0] / lw, w[1] / lw]
        sx, sy = (1 if w[0] > 0 else -1), (1 if w[1] > 0 else -1)
        k = -(u[0] * sx * da + u[1] * sy * db + dr)
        return [u[0], u[1], k], r / mp.sqrt(1 + da * da + db * db)
    if abs(w[0]) > tiny:
        sx = 1 if w[0] > 0 else -1
        return [M(sx), M(0), -(da + dr)], mp.inf
    sy = 1 if w[1] > 0 else -1
    return [M(0), M(sy), -(db + dr)], mp.inf


def tetra_faces(p):
    """The four faces of a tetrahedron, clockwise seen from outside
    (OpenSCAD's order)."""
    out = []
    for i, j, k, l in ((0, 1, 2, 3), (0, 1, 3, 2), (0, 2, 3, 1), (1, 2, 3, 0)):
        n = cross3([p[j][m] - p[i][m] for m in range(3)], [p[k][m] - p[i][m] for m in range(3)])
        inward = dot(n, [p[l][m] - p[i][m] for m in range(3)]) > 0
        out.append([i, j, k] if inward else [i, k, j])
    return out


def cross3(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def hull_planes(pts):
    """The facet planes (n, h) with n.x <= h inside, of points in general
    position: every triple with all other points on one side."""
    out = []
    n_ = len(pts)
    for i in range(n_):
        for j in range(i + 1, n_):
            for k in range(j + 1, n_):
                n = cross3([pts[j][m] - pts[i][m] for m in range(3)], [pts[k][m] - pts[i][m] for m in range(3)])
                h = dot(n, pts[i])
                side = [dot(n, q) - h for q in pts]
                if all(x <= 0 for x in side):
                    out.append((n, h))
                elif all(x >= 0 for x in side):
                    out.append(([-x for x in n], -h))
    return out


def pieces(a, b, c):
    """Intervals where a t^2 + 2 b t + c <= 0, a >= 0 (a cylinder's or a
    cone's side; a = 0: the line runs along it)."""
    if a == 0:
        return [(-mp.inf, mp.inf)] if c <= 0 else []
    return side_pieces(a, b, c)


def slab(o, d, lo, hi):
    """The interval of t with lo <= o + t d <= hi."""
    if d == 0:
        return (-mp.inf, mp.inf) if lo <= o <= hi else None
    a, b = (lo - o) / d, (hi - o) / d
    return (min(a, b), max(a, b))


def clipped(iv, s):
    if s is None:
        return []
    return [(max(a, s[0]), min(b, s[1])) for a, b in iv if max(a, s[0]) < min(b, s[1])]


def clip_box(o, d, lo, hi):
    a, b = -mp.inf, mp.inf
    for i in range(3):
        s = slab(o[i], d[i], lo[i], hi[i])
        if s is None:
            return None
        a, b = max(a, s[0]), min(b, s[1])
    return (a, b) if a < b else None


def convex_rays(p, n, rng):
    """Random rays at the middle part, rays from inside, and rays grazing
    1e-9 of the size inside: the capsule's cone, the box's rounded edges,
    the hull's edges; and rays at its corners."""
    c, s = p.c, p.s
    out = []

    def at(*rel):
        return [c[i] + rel[i] * s for i in range(3)]

    for _ in range(n):
        o, d, u = from_outside(at, rng, 0.15)
        out.append(("random", o, d))
        out.append(("inside", at(*(rng.uniform(-0.05, 0.05) for _ in range(3))), u))
    ulp = math.ulp(max(abs(x) for x in c) or 1.0)
    slim = max(SLIM, 8 * ulp / s)
    for j in range(n):
        a = 2 * math.pi * j / n
        if p.kind in SPHERE_HULLS:
            # Across the cone at z = 0.1, 1e-9 of the size inside it.
            z = M(0.1) * p.S
            rz = (p.rho1 + p.k * (z - p.z1t)) / p.S
            y = float(rz * (1 - M(slim)))
            o = at(-3.0 * math.cos(a) - y * math.sin(a), -3.0 * math.sin(a) + y * math.cos(a), 0.1)
            out.append(("grazing", o, [math.cos(a), math.sin(a), 0.0]))
        elif p.kind == "rounded_box":
            # Along a rounded vertical edge, 1e-9 of the size inside it.
            q = a / 4  # within the corner's quarter
            e = (1 - slim) * BOX_R
            x, y = BOX_SIDES[0] / 2 + e * math.cos(q), BOX_SIDES[1] / 2 + e * math.sin(q)
            out.append(("edge", at(x, y, -3.0), [0.0, 0.0, 1.0]))
            # At a rounded corner, from outside along the diagonal.
            corner = at(*(BOX_SIDES[i] / 2 + (1 - slim) * BOX_R / 3**0.5 for i in range(3)))
            o = at(3.0, 2.5, 3.5)
            out.append(("corner", o, unit([corner[i] - o[i] for i in range(3)])))
        elif p.kind == "chamfered_plate":
            # Across a corner's cone at mid-height, 1e-9 of the size inside
            # its side, horizontally.
            ch = {k: M(v) for k, v in CHAMFER.items()}
            zm = (ch["z1"] + ch["z3"]) / 2
            (a, b, r), _ = chamfer_section(ch, zm)
            q = math.pi / 2 * (j + 0.5) / n
            y = float(r * (1 - M(slim)))
            cx, cy = float(a), float(b)
            o = at(cx + 3.0 * math.cos(q) - y * math.sin(q), cy + 3.0 * math.sin(q) + y * math.cos(q), float(zm))
            out.append(("grazing", o, [-math.cos(q), -math.sin(q), 0.0]))
        elif p.kind == "lofted_plate":
            # Along a slanted edge's swept cylinder, 1e-9 of the size
            # inside its side, from its outer quarter.
            (ya, za), (yb, zb) = loft_edges([LOFT_A, LOFT_B, LOFT_R, LOFT_HC, LOFT_Z0, LOFT_Z1])[3 if j % 2 else 1]
            q = math.pi / 2 * (j + 0.5) / n
            w = [(1 - slim) * LOFT_R * math.cos(q), (1 - slim) * LOFT_R * math.sin(q) * (-1 if j % 2 else 1)]
            mid = [LOFT_A + w[0], (ya + yb) / 2 + w[1], (za + zb) / 2]
            along = unit([0.0, yb - ya, zb - za])
            out.append(("grazing", at(*(mid[i] - 3.0 * along[i] for i in range(3))), along))
        else:
            # Past the middle of a hull edge, 1e-9 of the size inside it.
            nplanes = len(p.planes)
            (n1, h1), (n2, h2) = p.planes[j % nplanes], p.planes[(j * 7 + 1) % nplanes]
            common = [q for q in p.pts if abs(dot(n1, q) - h1) < 1e-30 and abs(dot(n2, q) - h2) < 1e-30]
            if len(common) != 2:
                continue
            mid = [(common[0][i] + common[1][i]) / 2 for i in range(3)]
            centre = [sum(q[i] for q in p.pts) / len(p.pts) for i in range(3)]
            inward = [centre[i] - mid[i] for i in range(3)]
            li = mp.sqrt(dot(inward, inward))
            target = [float(mid[i] + inward[i] / li * slim * p.S) / s for i in range(3)]
            along = [common[1][i] - common[0][i] for i in range(3)]
            # A direction across the edge: the sum of the two faces'
            # normals turned about the edge by a quarter.
            w = cross3(along, [n1[i] / mp.sqrt(dot(n1, n1)) + n2[i] / mp.sqrt(dot(n2, n2)) for i in range(3)])
            d = unit([float(x) for x in w])
            o = at(*(target[i] - 3.0 * d[i] for i in range(3)))
            out.append(("edge", o, d))
    return out


# --------------------------------------------------------------------------
# Rays
# --------------------------------------------------------------------------


def from_outside(at, rng, spread):
    """A random ray from 3 sizes away towards a random point within
    `spread` sizes of the middle (origin, direction), and a random unit
    direction; `at` maps sizes to the world."""
    u = [rng.gauss(0, 1) for _ in range(3)]
    nu = sum(x * x for x in u) ** 0.5
    o = at(*(3 * x / nu for x in u))
    target = at(*(rng.uniform(-spread, spread) for _ in range(3)))
    return o, unit([target[i] - o[i] for i in range(3)]), unit(u)


def rays_for(p, n, rng):
    """(case, origin, direction) triples, all floats."""
    c, s = p.c, p.s
    out = []

    def at(*rel):
        return [c[i] + rel[i] * s for i in range(3)]

    for _ in range(n):
        o, d, u = from_outside(at, rng, 0.3)
        out.append(("random", o, d))
        inner = at(*(rng.uniform(-0.05, 0.05) for _ in range(3)))
        if p.kind == "torus":
            inner = at(1.0, 0.0, rng.uniform(-0.05, 0.05))
        out.append(("inside", inner, u))
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
    return [None if line == "miss" else [float(x) for x in line.split()] for line in out.stdout.splitlines()]


def check_ray(p, case, o, d, c, worst, worst_angle, failures):
    """csgrt's answer c (t and normal, or None) against the exact one."""
    exact = p.first(o, d)
    kind, size = p.kind, p.s
    where = (
        f"{kind} ({p.pose}) size {size:g} at offset {max(abs(x) for x in p.c):g}, "
        f"{case} ray {' '.join(repr(x) for x in (*o, *d))}"
    )
    key = (kind, p.pose, case)
    if (exact is None) != (c is None):
        failures.append(f"{where}: csgrt {c}, exact {exact}")
        worst[key] = (float("inf"), where)
        return
    if exact is None:
        return
    t, n = M(c[0]), v3(c[1:])
    scale = max(exact, M(size))
    err = float(abs(t - exact) / scale)
    if err > worst.get(key, (-1.0, ""))[0]:
        worst[key] = (err, where)
    if err > LIMIT:
        failures.append(f"{where}: relative error {err:.3g} > {LIMIT:g}")
    # The normal: a point off by LIMIT x scale along the ray sees the normal
    # turned by at most that distance over the world's curvature radius
    # there (smin x rho / kappa), plus the rounding of a unit vector.
    exact_n, rho = p.normal(o, d, exact)
    cosang = max(-1, min(1, dot(n, exact_n) / mp.sqrt(dot(n, n))))
    angle = float(mp.acos(cosang))
    kappa = p.smax / p.smin
    bound = float(LIMIT * scale * kappa / (p.smin * rho)) + ANGLE_FLOOR
    if angle / bound > worst_angle.get(key, (-1.0, 0.0))[0]:
        worst_angle[key] = (angle / bound, angle)
    if angle > bound:
        failures.append(f"{where}: normal {angle:.3g} rad from the exact one (bound {bound:.3g})")


def case_solid(kind, off, size, pose):
    cls = OffsetGlyph if kind == "offset_glyph" else Extruded if kind in EXTRUSIONS else Convexed if kind in CONVEXES else Prim
    return cls(kind, [off * x for x in [1.0, 0.7, 0.3]], size, pose)


def check_case(job):
    """(worst, worst angle, failures) of one placed solid's rays."""
    binary, same_as, kind, off, size, pose, rays = job
    p = case_solid(kind, off, size, pose)
    worst, worst_angle, failures = {}, {}, []
    with tempfile.TemporaryDirectory() as work:
        got = run(binary, p, rays, work)
        if same_as:
            if got != run(same_as, p, rays, work):
                failures.append(f"{kind} ({pose}) size {size:g} at offset {off:g}: not the same as {same_as}")
            worst[(kind, pose, "same")] = (0.0, "")
            return worst, worst_angle, failures
        for (case, o, d), c in zip(rays, got):
            check_ray(p, case, o, d, c, worst, worst_angle, failures)
    return worst, worst_angle, failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default="target/release/csgrt")
    ap.add_argument("--rays", type=int, default=12)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--report", default=None)
    ap.add_argument("--kinds", default=None, help="only these primitives (comma-separated)")
    ap.add_argument("--same-as", default=None, help="instead of exact answers, require another build's, to the byte")
    ap.add_argument("--first-failure", action="store_true", help="stop at the first case that fails (tools/oracle/mutants.py: one is enough)")
    a = ap.parse_args()
    rng = random.Random(20261122)
    worst = {}  # (kind, pose, case) -> (error, description)
    worst_angle = {}  # (kind, pose, case) -> (angle / bound, angle)
    failures = []
    kinds = ["sphere", "cube", "cylinder", "cone", "frustum", "torus"] + EXTRUSIONS + CONVEXES
    if a.kinds:
        kinds = [k for k in kinds if k in a.kinds.split(",")]
    # The rays drawn here, in order, from one seed; the cases checked two
    # (or as many as there are cores) at once, their worst merged in order.
    jobs = []
    for kind in kinds:
        poses = ["plain", "rotated+scaled"] if kind in ("twisted", "twisted_ellipse", "glyph", "cubic", "turned_cubic", "offset_glyph") else POSES
        for pose in poses:
            for off in OFFSETS:
                for size in SIZES:
                    p = case_solid(kind, off, size, pose)
                    maker = extrusion_rays if kind in EXTRUSIONS else convex_rays if kind in CONVEXES else rays_for
                    rays = [(case, *p.place(o, d)) for case, o, d in maker(p, a.rays, rng)]
                    jobs.append((a.csgrt, a.same_as, kind, off, size, pose, rays))
    with multiprocessing.Pool(os.cpu_count() or 1) as pool:
        for w, wa, fs in pool.imap(check_case, jobs):
            for key, v in w.items():
                if v[0] == float("inf") or v[0] > worst.get(key, (-1.0, ""))[0]:
                    worst[key] = v
            for key, v in wa.items():
                if v[0] > worst_angle.get(key, (-1.0, 0.0))[0]:
                    worst_angle[key] = v
            failures += fs
            if a.first_failure and fs:
                break  # (leaving the pool terminates the cases still running)
    lines = [
        "# Accuracy against exact arithmetic",
        "",
        "Generated by `tools/oracle/accuracy.py --report docs/accuracy.md`: csgrt's `--trace-rays` against",
        "mpmath at 50 digits, from the same f64 rays. Each primitive is placed at offsets 0, 1e3 and",
        "1e6 and sized 1e-3, 1 and 1e3; the error is |t - t_exact| / max(t_exact, size). The limit is",
        f"{LIMIT:g}.",
        "",
        "Each primitive is also rotated, scaled unevenly, and both (`rotate([..]) scale([..])`,",
        "exact rotations at 50 digits), and csgrt's normal is compared with the exact one: its angle",
        "must stay within LIMIT x scale over the curvature radius there (times the condition number",
        f"of the pose), plus {ANGLE_FLOOR:g} rad for rounding.",
        "",
        "| primitive | pose | case | worst relative error | worst normal angle (rad) | angle / bound | where |",
        "|---|---|---|---|---|---|---|",
    ]
    for key, (err, where) in sorted(worst.items()):
        ratio, angle = worst_angle.get(key, (0.0, 0.0))
        lines.append(f"| {key[0]} | {key[1]} | {key[2]} | {err:.3g} | {angle:.3g} | {ratio:.3g} | {where.split(',')[0]} |")
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
