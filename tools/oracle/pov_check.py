#!/usr/bin/env python3
"""Does csgrt's `--export-pov` say what the scene file says?

For each scene, csgrt writes POV-Ray 3.7 SDL; this tool parses the SDL back
with a reader of its own (POV-Ray's meaning: objects are placed by
`rotate` then `matrix <a..l>`, a row-vector transform p' = p M with the
last three numbers the translation; `rotate x*90` turns +y to +z; `plane
{ z, 0 }` is z <= 0; a box, sphere, cylinder, cone and torus their usual
solids; union, intersection, difference with POV-Ray's first-minus-rest),
reads the same scene with the oracle's own reader (tools/oracle/scene/), and
compares:

* the solid: inside or outside, at 4000 points of the scene's box (and a
  margin around it) and 200 in each leaf's box, for the whole tree; a point within 1e-9 of the size
  of any leaf's surface is skipped;
* each leaf: every exported leaf must be the same solid as one leaf of the
  file (the same answer at every sample point; a part a difference takes
  away without the clearance csgrt gives it, `translate scale translate`
  after its matrix, a scale within 1 ± 2e-4, whose band is not judged in
  the whole solid), with its colour, its
  transmission and its finish (ambient, diffuse, phong, phong_size,
  reflection) the file's material;
* the camera: location, look_at, sky and angle the file's view, `right`
  the image's aspect; the lights (the file's, or csgrt's rig about the
  camera): their colours, positions, shadows, and for a directional light
  its direction (point_at minus location); the background and the summed
  ambient light. Colours are compared as linear values (the file's sRGB
  decoded).

Usage: pov_check.py [--csgrt BIN] SCENE...   (exit 1 if any differs)
"""

import argparse
import math
import multiprocessing
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from tools.oracle import scene as reader  # noqa: E402
from tools.oracle.oracle import ray_sets  # noqa: E402

WIDTH, HEIGHT = 40, 30
# csgrt's clearance (src/export/pov.rs CLEARANCE): a part a difference takes
# away is scaled by at most 1 ± 2 CLEARANCE.
CLEARANCE = 1e-4

# --------------------------------------------------------------------------
# SDL: tokens and objects
# --------------------------------------------------------------------------

TOKEN = re.compile(r"\s+|//[^\n]*|(#version|[A-Za-z_][A-Za-z_0-9]*|[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?|[{}<>,*/-])")


def tokens(text):
    out = []
    for m in TOKEN.finditer(text):
        if m.group(1):
            out.append(m.group(1))
    return out


class Sdl:
    def __init__(self, text):
        self.t = tokens(text)
        self.i = 0

    def peek(self):
        return self.t[self.i] if self.i < len(self.t) else None

    def take(self, want=None):
        x = self.t[self.i]
        if want is not None and x != want:
            raise ValueError(f"expected {want!r} at token {self.i}, found {x!r}")
        self.i += 1
        return x

    def number(self):
        x = self.take()
        if x == "-":
            return -float(self.take())
        return float(x)

    def vector(self):
        self.take("<")
        out = [self.number()]
        while self.peek() == ",":
            self.take()
            out.append(self.number())
        self.take(">")
        return np.array(out)

    def block(self):
        """The rest of a `{ ... }` whose `{` was read, skipped."""
        depth = 1
        while depth:
            x = self.take()
            depth += {"{": 1, "}": -1}.get(x, 0)


SHAPES = ("box", "sphere", "cylinder", "cone", "torus", "plane", "prism", "lathe", "mesh2")


def even_odd(loops, q):
    """Points q (n x 2) inside closed loops by the even-odd rule."""
    inside = np.zeros(len(q), dtype=bool)
    for l in loops:
        for a, b in zip(l, np.roll(l, -1, axis=0)):
            cross = (a[1] > q[:, 1]) != (b[1] > q[:, 1])
            with np.errstate(divide="ignore", invalid="ignore"):
                x = a[0] + (q[:, 1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
            inside ^= cross & (x > q[:, 0])
    return inside


def bezier_even_odd(segments, q):
    """Points q (n x 2) inside closed loops of Bézier segments (each a
    (k, 2) array of control points, k = 2 for a line, 3 a quadratic, 4 a
    cubic) by the even-odd rule: the crossings of the line from each point
    along +x, half-open in y like even_odd. A cubic that is a raised
    quadratic or line (POV-Ray's bezier_spline carries them so) is lowered
    back. Each curve is cut where y' vanishes into pieces monotone in y; a
    quadratic piece's crossing comes from the quadratic formula, a cubic's
    by bisection (60 halvings)."""
    inside = np.zeros(len(q), dtype=bool)
    for P in segments:
        P = lowered(np.asarray(P, float))
        if len(P) == 2:
            inside ^= even_odd_segment(P[0], P[1], q)
            continue
        yk = bezier_power(P[:, 1])
        xk = bezier_power(P[:, 0])
        dy = np.polynomial.polynomial.Polynomial(yk).deriv()
        cuts = [0.0] + sorted(float(r.real) for r in dy.roots() if abs(r.imag) < 1e-12 and 0 < r.real < 1) + [1.0]
        for u0, u1 in zip(cuts[:-1], cuts[1:]):
            a, b = bezier_at(P, u0), bezier_at(P, u1)
            cross = (a[1] > q[:, 1]) != (b[1] > q[:, 1])
            if not cross.any():
                continue
            idx = np.nonzero(cross)[0]
            y = q[idx, 1]
            if len(P) == 3:
                u = quadratic_root_in(yk[2], yk[1], yk[0] - y, u0, u1)
            else:
                lo, hi = np.full(len(idx), u0), np.full(len(idx), u1)
                rising = b[1] > a[1]
                for _ in range(60):
                    mid = 0.5 * (lo + hi)
                    above = bezier_at(P, mid)[..., 1] > y
                    go_lo = above if rising else ~above
                    hi = np.where(go_lo, mid, hi)
                    lo = np.where(go_lo, lo, mid)
                u = 0.5 * (lo + hi)
            x = np.polynomial.polynomial.polyval(u, xk)
            inside[idx] ^= x > q[idx, 0]
    return inside


def lowered(P):
    """A Bézier of degree 3 that is exactly a raised quadratic (or line),
    as that (to rounding)."""
    if len(P) != 4:
        return P
    scale = max(1.0, float(np.abs(P).max()))
    if np.abs(P[0] - 3 * P[1] + 3 * P[2] - P[3]).max() > 1e-12 * scale:
        return P
    c = (3 * P[1] - P[0]) / 2
    if np.abs(P[0] - 2 * c + P[3]).max() <= 1e-12 * scale:
        return np.array([P[0], P[3]])
    return np.array([P[0], c, P[3]])


def quadratic_root_in(a, b, c, u0, u1):
    """For each c (an array), the root of a u^2 + b u + c in [u0, u1] (the
    polynomial is monotone there and changes sign), by the formula that
    does not cancel, clipped to the piece."""
    if abs(a) <= 1e-15 * max(abs(b), 1e-300):
        return np.clip(-c / b, u0, u1)
    disc = np.sqrt(np.maximum(b * b - 4 * a * c, 0.0))
    qq = -0.5 * (b + np.copysign(disc, b))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1, r2 = qq / a, np.where(qq != 0, c / qq, -b / (2 * a))
    mid = 0.5 * (u0 + u1)
    pick = np.abs(r1 - mid) <= np.abs(r2 - mid)
    return np.clip(np.where(pick, r1, r2), u0, u1)


def even_odd_segment(a, b, q):
    cross = (a[1] > q[:, 1]) != (b[1] > q[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        x = a[0] + (q[:, 1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
    return cross & (x > q[:, 0])


def bezier_power(c):
    """Power-basis coefficients (lowest first) of a Bézier coordinate."""
    k = len(c) - 1
    return [math.comb(k, j) * sum((-1) ** (j - i) * math.comb(j, i) * c[i] for i in range(j + 1)) for j in range(k + 1)]


def bezier_at(P, u):
    """De Casteljau's point of the Bézier P at parameter(s) u."""
    u = np.asarray(u, float)[..., None]
    pts = [np.broadcast_to(p, u.shape[:-1] + (2,)) for p in P]
    while len(pts) > 1:
        pts = [(1 - u) * a + u * b for a, b in zip(pts[:-1], pts[1:])]
    return pts[0]


def bezier_loops(pts):
    """POV-Ray's bezier_spline point list: four points a segment, a
    sub-prism closing where a segment ends on its first segment's start."""
    if len(pts) % 4:
        raise ValueError("a bezier_spline whose point count is not a multiple of 4")
    segs, out, start = [np.array(pts[i : i + 4]) for i in range(0, len(pts), 4)], [], 0
    for i, sg in enumerate(segs):
        if i > start and not np.array_equal(sg[0], segs[i - 1][3]):
            raise ValueError("a bezier_spline segment that does not start where the last ended")
        if np.array_equal(sg[3], segs[start][0]):
            out.extend(segs[start : i + 1])
            start = i + 1
    if start != len(segs):
        raise ValueError("a bezier_spline outline that does not close")
    return out


def sub_polygons(pts):
    """POV-Ray's point list of a prism or lathe: a sub-polygon closes
    where its first point comes again."""
    out, start = [], 0
    for i in range(1, len(pts)):
        if i > start and np.array_equal(pts[i], pts[start]):
            out.append(np.array(pts[start:i]))
            start = i + 1
    return out


class PovLeaf:
    def __init__(self, kind, params, matrix, texture, own=None, clearance=None):
        self.kind, self.params, self.matrix, self.texture = kind, params, matrix, texture
        # The leaf's own `matrix`, and the clearance csgrt puts after it
        # (`translate scale translate`: a part a difference takes away
        # grown clear of the faces it shares), if any.
        self.own = matrix if own is None else own
        self.clearance = clearance

    def inside_own(self, pts):
        """`inside` without the clearance: the file's leaf."""
        return PovLeaf(self.kind, self.params, self.own, self.texture).inside(pts)

    def inside(self, pts):
        """Inside tests of world points (n x 3), in POV-Ray's terms."""
        q = (pts - self.matrix[:3, 3]) @ np.linalg.inv(self.matrix[:3, :3]).T
        p = self.params
        if self.kind == "box":
            return np.all((q >= p["lo"]) & (q <= p["hi"]), axis=1)
        if self.kind == "sphere":
            return np.sum((q - p["c"]) ** 2, axis=1) <= p["r"] ** 2
        if self.kind in ("cylinder", "cone"):
            return frustum_inside(q, p["a"][2], p["b"][2], p["ra"], p["rb"])
        if self.kind == "prism":
            # Swept along y; the section at height y is the polygon, scaled
            # by y for a conic sweep.
            y = q[:, 1]
            w = y if p["sweep"] == "conic_sweep" else np.ones(len(q))
            with np.errstate(divide="ignore", invalid="ignore"):
                flat = np.column_stack([q[:, 0] / w, q[:, 2] / w])
            region = bezier_even_odd(p["segments"], flat) if "segments" in p else even_odd(p["loops"], flat)
            return (y >= p["h0"]) & (y <= p["h1"]) & (w > 0) & region
        if self.kind == "lathe":
            rz = np.column_stack([np.hypot(q[:, 0], q[:, 2]), q[:, 1]])
            return bezier_even_odd(p["segments"], rz) if "segments" in p else even_odd(p["loops"], rz)
        if self.kind == "mesh2":
            # POV-Ray's inside test of a mesh: the parity of its crossings
            # along inside_vector.
            if len(p["tris"]) > 64:
                import manifold3d as mf

                if "solid" not in p:
                    # The exported triangles as manifold3d takes them (any
                    # winding works for a parity count); numpy if it will not.
                    t = p["tris"].astype(np.uint32)
                    m = mf.Manifold(mf.Mesh64(vert_properties=p["verts"], tri_verts=t))
                    if m.status() != mf.Error.NoError or m.is_empty():
                        m = mf.Manifold(mf.Mesh64(vert_properties=p["verts"], tri_verts=t[:, [0, 2, 1]].copy()))
                    p["solid"] = m if m.status() == mf.Error.NoError and not m.is_empty() else None
                if p["solid"] is not None:
                    return segment_parity(p["solid"], p["verts"], q, p["inside"])
            return ray_parity(p["verts"], p["tris"], q, p["inside"])
        if self.kind == "torus":
            # rotate x*90 first: object (x, y, z) came from torus coords
            # (x, -z, y)... in POV-Ray the torus lies in the x-z plane.
            rx = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0.0]])
            u = q @ rx  # back to the torus's own x-z plane
            return (np.hypot(u[:, 0], u[:, 2]) - p["R"]) ** 2 + u[:, 1] ** 2 <= p["r"] ** 2
        return q[:, 2] <= p["d"]


class PovOp:
    def __init__(self, op, children):
        self.op, self.children = op, children

    def inside(self, pts):
        return combine(self.op, [c.inside(pts) for c in self.children])


def combine(op, ins):
    """A CSG operation on its operands' inside answers (difference: the
    first minus the rest, in POV-Ray and in OpenSCAD alike)."""
    if op == "union":
        return np.any(ins, axis=0)
    if op == "intersection":
        return np.all(ins, axis=0)
    if op == "xor":
        return np.sum(ins, axis=0) % 2 == 1
    return ins[0] & ~np.any(ins[1:], axis=0)


def ray_parity(verts, tris, q, d):
    """Whether each point q is inside the triangles by the parity of their
    crossings with the half-line q + t d, t > 0 (Möller–Trumbore)."""
    a, b, c = verts[tris[:, 0]], verts[tris[:, 1]], verts[tris[:, 2]]
    e1, e2 = b - a, c - a
    pv = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, pv)
    ok = np.abs(det) > 1e-300
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    count = np.zeros(len(q), dtype=np.int64)
    for k in range(0, len(q), 512):
        qq = q[k : k + 512][:, None, :]
        tv = qq - a[None]
        u = np.einsum("pij,ij->pi", tv, pv) * inv
        qv = np.cross(tv, e1[None])
        v = (qv @ d) * inv
        t = np.einsum("pij,ij->pi", qv, e2) * inv
        hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        count[k : k + 512] = hit.sum(axis=1)
    return count % 2 == 1


def mesh_inside(leaf, q):
    """Whether object points q are inside a polyhedron: the parity of the
    crossings manifold3d finds along a fixed segment out of its box, on
    the oracle's own triangulation of the file's faces (a mesh of many
    faces), or the generalized winding number (a few)."""
    p = leaf.params
    if len(p["faces"]) <= 64:
        return winding_inside(p["points"], p["faces"], q)
    from tools.oracle import oracle

    return segment_parity(oracle.polyhedron_solid(leaf), p["points"], q, np.array([0.5734621, 0.6143793, 0.5420587]))


def segment_parity(solid, verts, q, d):
    """Whether points q are inside a manifold3d solid over `verts`: the
    parity of its crossings along the segment from each point along d out
    past the points' box."""
    far = 4.0 * float(np.linalg.norm(verts.max(axis=0) - verts.min(axis=0))) + 1.0
    d = d / np.linalg.norm(d)
    return np.array([len(solid.ray_cast(x.tolist(), (x + far * d).tolist())) % 2 == 1 for x in q])


def winding_inside(pts, faces, q):
    """Whether points q are inside a polyhedron of planar faces (any
    shape, wound alike): its generalized winding number, the sum of its
    faces' solid angles over 4 pi (each face as the fan from its first
    point, which sums signed triangles right for non-convex faces too)."""
    tris = np.array([[f[0], f[k], f[k + 1]] for f in faces for k in range(1, len(f) - 1)])
    w = np.zeros(len(q))
    for k in range(0, len(q), 512):
        qq = q[k : k + 512][:, None, :]
        a, b, c = pts[tris[:, 0]][None] - qq, pts[tris[:, 1]][None] - qq, pts[tris[:, 2]][None] - qq
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        num = np.einsum("pij,pij->pi", a, np.cross(b, c))
        den = la * lb * lc + np.einsum("pij,pij->pi", a, b) * lc + np.einsum("pij,pij->pi", a, c) * lb + np.einsum("pij,pij->pi", b, c) * la
        w[k : k + 512] = 2 * np.arctan2(num, den).sum(axis=1) / (4 * math.pi)
    return np.abs(w) > 0.5


def frustum_inside(q, z0, z1, r0, r1):
    """Points q of the solid between z0 and z1 whose radius goes from r0
    to r1 (a cylinder, a cone frustum or a cone)."""
    f = (q[:, 2] - z0) / (z1 - z0)
    r = r0 + (r1 - r0) * f
    return (f >= 0) & (f <= 1) & (np.hypot(q[:, 0], q[:, 1]) <= r)


def pov_matrix(nums):
    """POV-Ray's matrix <a..l>: rows of a row-vector transform."""
    m = np.eye(4)
    rows = np.array(nums).reshape(4, 3)
    m[:3, :3] = rows[:3].T
    m[:3, 3] = rows[3]
    return m


def read_object(s, kind):
    s.take("{")
    p = {}
    if kind == "box":
        p["lo"] = s.vector()
        s.take(",")
        p["hi"] = s.vector()
    elif kind == "sphere":
        p["c"] = s.vector()
        s.take(",")
        p["r"] = s.number()
    elif kind == "cylinder":
        p["a"] = s.vector()
        s.take(",")
        p["b"] = s.vector()
        s.take(",")
        p["ra"] = p["rb"] = s.number()
    elif kind == "cone":
        p["a"] = s.vector()
        s.take(",")
        p["ra"] = s.number()
        s.take(",")
        p["b"] = s.vector()
        s.take(",")
        p["rb"] = s.number()
    elif kind == "torus":
        p["R"] = s.number()
        s.take(",")
        p["r"] = s.number()
    elif kind == "mesh2":
        for section, key in (("vertex_vectors", "verts"), ("face_indices", "tris")):
            s.take(section)
            s.take("{")
            count = int(s.number())
            rows = []
            for _ in range(count):
                s.take(",")
                rows.append(s.vector())
            s.take("}")
            p[key] = np.array(rows, dtype=float if key == "verts" else np.int64).reshape(-1, 3)
        s.take("inside_vector")
        p["inside"] = np.array(s.vector(), dtype=float)
    elif kind in ("prism", "lathe"):
        if kind == "prism":
            p["sweep"] = s.take()
        spline = s.take()
        if spline not in ("linear_spline", "bezier_spline"):
            raise ValueError(f"a {kind} with {spline}")
        if kind == "prism":
            p["h0"] = s.number()
            s.take(",")
            p["h1"] = s.number()
            s.take(",")
        count = int(s.number())
        pts = []
        for k in range(count):
            s.take(",")
            pts.append(s.vector())
        if spline == "bezier_spline":
            p["segments"] = bezier_loops([np.array(x[:2]) for x in pts])
        else:
            p["loops"] = sub_polygons([np.array(x[:2]) for x in pts])
        if kind == "lathe" and "loops" in p and len(p["loops"]) != 1:
            raise ValueError("a lathe of several outlines")
    else:
        axis = s.take()
        if axis != "z":
            raise ValueError(f"a plane along {axis}")
        s.take(",")
        p["d"] = s.number()
    t = read_object_tail(s, kind)
    return PovLeaf(kind, p, t.matrix, t.texture, t.own, t.clearance)


class Tail:
    def __init__(self, matrix, texture, own=None, clearance=None):
        self.matrix, self.texture = matrix, texture
        self.own, self.clearance = own, clearance


def read_object_tail(s, kind):
    """An object's transforms (applied in order) and texture, to its `}`:
    the whole transform, the one before any `translate` or `scale` (the
    object's own `matrix`), and the scale factors of `scale` (csgrt's
    clearance)."""
    m, texture = np.eye(4), {}
    own, clearance = None, None
    while s.peek() != "}":
        w = s.take()
        if w in ("translate", "scale"):
            if own is None:
                own, clearance = m.copy(), []
            t = np.eye(4)
            if w == "translate":
                t[:3, 3] = s.vector()
            else:
                k = s.number()
                t[:3, :3] *= k
                clearance.append(k)
            m = t @ m
            continue
        if w == "rotate":
            axis = s.take()
            s.take("*")
            ang = s.number()
            if (axis, ang) != ("x", 90.0) or kind != "torus":
                raise ValueError(f"rotate {axis}*{ang} on a {kind}")
        elif w == "matrix":
            m = pov_matrix(s.vector()) @ m
        elif w == "texture":
            s.take("{")
            while s.peek() != "}":
                part = s.take()
                s.take("{")
                if part == "pigment":
                    s.take("color")
                    s.take("rgbt")
                    texture["rgbt"] = s.vector()
                    s.take("}")
                elif part == "finish":
                    while s.peek() != "}":
                        key = s.take()  # before the value: Python reads the right side first
                        texture[key] = s.number()
                    s.take("}")
                else:
                    s.block()
            s.take("}")
        elif w == "interior":
            s.take("{")
            s.take("ior")
            texture["ior"] = s.number()
            s.take("}")
        else:
            raise ValueError(f"unexpected {w!r} in a {kind}")
    s.take("}")
    return Tail(m, texture, own, clearance)


class PovPlaced:
    """`object { inner ... }`: the inner object under the object's
    transforms, with its texture."""

    kind = "object"

    def __init__(self, inner, matrix, texture):
        self.inner, self.matrix, self.texture = inner, matrix, texture

    def inside(self, pts):
        q = (pts - self.matrix[:3, 3]) @ np.linalg.inv(self.matrix[:3, :3]).T
        return self.inner.inside(q)


def read_node(s, word):
    if word in SHAPES:
        return read_object(s, word)
    if word == "object":
        # object { INNER transforms and texture }: the inner object placed.
        s.take("{")
        inner = read_node(s, s.take())
        outer = read_object_tail(s, "object")
        return PovPlaced(inner, outer.matrix, outer.texture)
    s.take("{")
    kids = []
    while s.peek() != "}":
        kids.append(read_node(s, s.take()))
    s.take("}")
    return PovOp(word, kids)


def read_sdl(text):
    s = Sdl(text)
    out = {"lights": [], "root": None}
    while s.peek() is not None:
        w = s.take()
        if w == "#version":
            s.number()
        elif w == "global_settings":
            s.take("{")
            while s.peek() != "}":
                k = s.take()
                if k == "ambient_light":
                    s.take("color")
                    s.take("rgb")
                    out["ambient"] = s.vector()
                elif k == "adc_bailout":
                    s.number()
                    s.take("/")
                    s.number()
                else:
                    s.number()
            s.take("}")
        elif w == "background":
            s.take("{")
            s.take("color")
            s.take("rgb")
            out["background"] = s.vector()
            s.take("}")
        elif w == "camera":
            s.take("{")
            cam = {}
            while s.peek() != "}":
                k = s.take()
                if k == "perspective":
                    continue
                if k in ("location", "sky", "look_at"):
                    cam[k] = s.vector()
                elif k == "angle":
                    cam[k] = s.number()
                elif k == "right":
                    s.take("-")
                    s.take("x")
                    s.take("*")
                    cam[k] = s.number()
                elif k == "up":
                    cam[k] = s.take()
            s.take("}")
            out["camera"] = cam
        elif w == "light_source":
            s.take("{")
            light = {"at": s.vector()}
            while s.peek() != "}":
                k = s.take()
                if k == "color":
                    s.take("rgb")
                    light["color"] = s.vector()
                elif k == "parallel":
                    light["parallel"] = True
                elif k == "shadowless":
                    light["shadowless"] = True
                elif k == "point_at":
                    light["point_at"] = s.vector()
            s.take("}")
            out["lights"].append(light)
        else:
            out["root"] = read_node(s, w)
    return out


# --------------------------------------------------------------------------
# The file, through the oracle's reader
# --------------------------------------------------------------------------


def flat_inside(f, q2):
    """Points q2 (n x 2) inside a 2-D tree of scene.py."""
    if f[0] == "poly":
        return even_odd(f[1], q2)
    if f[0] == "curves":
        return bezier_even_odd([reader.bezier_points(a, c, b) for a, c, b in reader.curve_pieces(f)], q2)
    if f[0] == "ellipse":
        u = np.linalg.solve(f[1], (q2 - f[2]).T).T
        return np.sum(u**2, axis=1) <= 1.0
    if f[0] == "faces":
        return np.any([even_odd([l], q2) for l in f[1]], axis=0)
    return combine(f[1], [flat_inside(k, q2) for k in f[2]])


def flat_leaves(f):
    if f[0] in ("poly", "ellipse", "curves", "faces"):
        return [f]
    return [x for k in f[2] for x in flat_leaves(k)]


TWIST_ERROR = '#error "csgrt: a twisted or unevenly scaled linear_extrude has no POV-Ray equivalent"'
SECTION_ERROR = '#error "csgrt: projection(cut = true) has no POV-Ray equivalent"'
HULL_ERROR = '#error "csgrt: hull() and minkowski() have no POV-Ray equivalent"'
SHADOW_ERROR = '#error "csgrt: projection(cut = false) has no POV-Ray equivalent"'
XOR_ERROR = '#error "csgrt: a drawing\'s outlines combined even-odd have no POV-Ray equivalent"'
OFFSET_ERROR = '#error "csgrt: offset() of curved outlines has no POV-Ray equivalent"'


def has_faces(f):
    return f is not None and (f[0] == "faces" or f[0] == "op" and any(has_faces(k) for k in f[2]))


def has_bands(f):
    """Whether a 2-D tree holds a curved outline offset (scene.py's
    ("bands", d) mark)."""
    return f is not None and f[0] == "op" and (len(f) == 4 and f[3][0] == "bands" or any(has_bands(k) for k in f[2]))


def has_xor(f):
    return f is not None and f[0] == "op" and (f[1] == "xor" or any(has_xor(k) for k in f[2]))


def extrusion_parts(leaf, q):
    """(whole, [parts]) inside answers at object points q: the extrusion,
    and the solid each 2-D leaf sweeps (and each half-space cutting a
    partial turn) — the leaves csgrt makes of it."""
    p = leaf.params
    if leaf.kind == "linear_extrude" and reader.twisted(p):
        z0, h, (sx, sy) = p["z0"], p["h"], p["scale2"]
        t = (q[:, 2] - z0) / h
        sg = np.column_stack([1 + (sx - 1) * t, 1 + (sy - 1) * t])
        slab = (t >= 0) & (t <= 1) & np.all(sg > 0, axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = q[:, :2] / np.where(sg > 0, sg, 1.0)
        a = np.radians(p["twist"]) * t
        q2 = np.column_stack([np.cos(a) * u[:, 0] - np.sin(a) * u[:, 1], np.sin(a) * u[:, 0] + np.cos(a) * u[:, 1]])
        whole = slab & flat_inside(p["flat"], q2)
        return whole, [slab & flat_inside(x, q2) for x in flat_leaves(p["flat"])]
    if leaf.kind == "linear_extrude":
        z0, h, sc = p["z0"], p["h"], p["scale"]
        w = 1 + (sc - 1) * (q[:, 2] - z0) / h
        slab = (q[:, 2] >= z0) & (q[:, 2] <= z0 + h) & (w > 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            q2 = q[:, :2] / np.where(w > 0, w, 1.0)[:, None]
        whole = slab & flat_inside(p["flat"], q2)
        return whole, [slab & flat_inside(x, q2) for x in flat_leaves(p["flat"])]
    f, flip = reader.revolve_setup(p)
    q2 = np.column_stack([np.hypot(q[:, 0], q[:, 1]), q[:, 2]])
    whole = flat_inside(f, q2)
    parts = [flat_inside(x, q2) for x in flat_leaves(f)]
    if p["angle"] != 360:
        cuts = [q @ n <= 0 for n in reader.wedge_normals(p["angle"], flip)]
        whole &= combine("intersection" if abs(p["angle"]) <= 180 else "union", cuts)
        parts += cuts
    return whole, parts


def hull_inside(leaf, pts):
    """Whether points are inside a hull or a Minkowski sum of the file's
    polytopes (csgrt exports only those, as a mesh; curved ones stop the
    export): manifold3d's hull or sum of the oracle's own meshes of the
    parts (exact for polytopes), by segment parity."""
    from tools.oracle.oracle import mesh as oracle_mesh

    m = oracle_mesh.leaf_mesh(leaf, 64, 1e6)
    verts = m.to_mesh().vert_properties[:, :3]
    return segment_parity(m, verts, pts, np.array([0.5734621, 0.6143793, 0.5420587]))


def leaf_inside(leaf, pts):
    if leaf.kind in ("hull", "minkowski"):
        return hull_inside(leaf, pts)
    q = (pts - leaf.matrix[:3, 3]) @ np.linalg.inv(leaf.matrix[:3, :3]).T
    p = leaf.params
    if leaf.kind in reader.EXTRUSIONS:
        return extrusion_parts(leaf, q)[0]
    if leaf.kind == "sphere":
        return np.sum(q**2, axis=1) <= p["r"] ** 2
    if leaf.kind == "cube":
        lo = -p["size"] / 2 if p["center"] else np.zeros(3)
        return np.all((q >= lo) & (q <= lo + p["size"]), axis=1)
    if leaf.kind == "cylinder":
        z0 = -p["h"] / 2 if p["center"] else 0.0
        return frustum_inside(q, z0, z0 + p["h"], p["r1"], p["r2"])
    if leaf.kind == "torus":
        return (np.hypot(q[:, 0], q[:, 1]) - p["R"]) ** 2 + q[:, 2] ** 2 <= p["r"] ** 2
    if leaf.kind == "polyhedron":
        return mesh_inside(leaf, q)
    return q @ p["normal"] <= p["offset"]


def tree_inside(node, pts):
    if node is None:
        return np.zeros(len(pts), dtype=bool)
    if isinstance(node, reader.Leaf):
        return leaf_inside(node, pts)
    return combine(node.op, [tree_inside(c, pts) for c in node.children])


def pov_leaves(node):
    if isinstance(node, (PovLeaf, PovPlaced)):
        yield node
    elif node is not None:
        for c in node.children:
            yield from pov_leaves(c)


def near_any_surface(sc, pts, eps):
    """Points whose inside answer flips within eps along some axis, for
    any leaf: they are too close to a surface to judge."""
    out = np.zeros(len(pts), dtype=bool)
    for leaf in sc.leaves:
        base = leaf_inside(leaf, pts)
        for k in range(3):
            for s in (-1, 1):
                d = np.zeros(3)
                d[k] = s * eps
                out |= leaf_inside(leaf, pts + d) != base
    return out


def close(a, b, tol=1e-9):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= tol * np.maximum(1.0, np.abs(b))))


def texture_problems(pl, mat):
    """How the exported leaf's texture differs from material mat."""
    out = []
    tex = pl.texture
    want_t = dict(rgbt=[*reader.srgb_decode(mat["color"]), mat["kt"]], ambient=mat["ka"], diffuse=mat["kd"], phong=mat["ks"],
                  phong_size=mat["ns"], reflection=mat["kr"])
    if mat["kt"] > 0:
        want_t["ior"] = mat["ior"]
    for k, w in want_t.items():
        if k not in tex or not close(tex[k], w):
            out.append(f"the exported {pl.kind}'s {k} is {tex.get(k)}, the file says {w}")
    return out


def check(path, binary):
    sc = reader.read(path)
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "s.pov")
        image = os.path.join(work, "s.png")
        dump = os.path.join(work, "s.json")
        subprocess.run(
            [binary, path, "--size", f"{WIDTH}x{HEIGHT}", "--export-pov", out, "-o", image, "--dump-scene", dump, "-q"],
            check=True,
        )
        with open(out) as f:
            text = f.read()
        # The box csgrt framed (the oracle checks it against its own mesh).
        framed = ray_sets.framed_box(dump)
        if TWIST_ERROR in text:
            # POV-Ray has no twisted prism: the export must stop POV-Ray
            # with the reason, and only for a scene that twists.
            twists = [x for x in sc.leaves if x.kind == "linear_extrude" and reader.twisted(x.params)]
            return [] if twists else ["the export refuses a twisted prism the file does not have"]
        if HULL_ERROR in text:
            # POV-Ray has no convex hull nor Minkowski sum: the same.
            hulls = [x for x in sc.leaves if x.kind in ("hull", "minkowski")]
            return [] if hulls else ["the export refuses a hull the file does not have"]
        if SHADOW_ERROR in text:
            # Nor a shadow of triangles: the same, for projections' shadows.
            shadows = [x for x in sc.leaves if x.kind in reader.EXTRUSIONS and has_faces(x.params.get("flat"))]
            return [] if shadows else ["the export refuses a shadow the file does not have"]
        if XOR_ERROR in text:
            # Nor an even-odd combination of solids: the same, for drawings
            # whose arcs, ellipses or strokes join their outlines by parity.
            xors = [x for x in sc.leaves if x.kind in reader.EXTRUSIONS and has_xor(x.params.get("flat"))]
            return [] if xors else ["the export refuses an even-odd drawing the file does not have"]
        if OFFSET_ERROR in text:
            # Nor offset curves: the same, for curved outlines offset.
            grown = [x for x in sc.leaves if x.kind in reader.EXTRUSIONS and has_bands(x.params.get("flat"))]
            return [] if grown else ["the export refuses an offset of curves the file does not have"]
        if SECTION_ERROR in text:
            # Nor a solid made of another's slice: the same, for projections.
            cuts = [x for x in sc.leaves if reader.has_slice(x)]
            return [] if cuts else ["the export refuses a projection the file does not have"]
        sdl = read_sdl(text)
    bad = []
    # Camera, lights, background.
    view = sc.view(WIDTH, HEIGHT, framed)
    eye, lookat, up, fov = view
    cam = sdl["camera"]
    for k, want in (("location", eye), ("look_at", lookat), ("sky", up), ("angle", fov), ("right", WIDTH / HEIGHT)):
        if not close(cam[k], want):
            bad.append(f"camera {k} is {cam[k]}, the file says {want}")
    # Colours in linear values, decoded from the file's sRGB.
    background = reader.srgb_decode(sc.background)
    if not close(sdl["background"], background):
        bad.append(f"background {sdl['background']}, the file says {background} (linear)")
    seen = sc.lights_seen_by(view)
    ambient = sum((c for kind, c, _, _ in seen if kind == "ambient"), np.zeros(3))
    if not close(sdl.get("ambient", np.zeros(3)), ambient):
        bad.append(f"ambient light {sdl.get('ambient')}, the file says {ambient}")
    lights = [(kind, c, x, shadows) for kind, c, x, shadows in seen if kind != "ambient"]
    if len(lights) != len(sdl["lights"]):
        bad.append(f"{len(sdl['lights'])} light sources, the file has {len(lights)}")
    for (kind, c, x, shadows), got in zip(lights, sdl["lights"]):
        if got.get("shadowless", False) == shadows:
            bad.append(f"a light {'without' if got.get('shadowless') else 'with'} shadows, the file's {'casts' if shadows else 'casts none'}")
        if not close(got["color"], c):
            bad.append(f"a light's colour is {got['color']}, the file says {c}")
        if kind == "point" and (got.get("parallel") or not close(got["at"], x)):
            bad.append(f"a point light at {got['at']}, the file says {x}")
        if kind == "directional":
            d = got.get("point_at", np.zeros(3)) - got["at"]
            if not got.get("parallel") or not close(d / np.linalg.norm(d), x / np.linalg.norm(x)):
                bad.append(f"a directional light along {d}, the file says {x}")
    # The solid and its leaves, at sample points.
    boxes = reader.bounded_boxes(sc) or [reader.UNIT]
    lo, hi = reader.bounded_box(sc, reader.UNIT)
    size = float(np.linalg.norm(hi - lo))
    rng = np.random.default_rng(12)
    pts = [lo - 0.1 * size + rng.random((4000, 3)) * (hi - lo + 0.2 * size)]
    # And 200 points in each bounded leaf's own box, so that a small or
    # thin leaf is told apart from its neighbours.
    for blo, bhi in boxes:
        pad = 0.05 * (bhi - blo)
        pts.append(blo - pad + rng.random((200, 3)) * (bhi - blo + 2 * pad))
    pts = np.concatenate(pts)
    keep = ~near_any_surface(sc, pts, 1e-9 * size)
    pts = pts[keep]
    # A clearance (csgrt grows a part a difference takes away, see
    # src/export/pov.rs) may change the answer only where it moves the
    # leaf's surface: such points are not judged. Its scale is bounded.
    band = np.zeros(len(pts), dtype=bool)
    for pl in pov_leaves(sdl["root"]):
        if getattr(pl, "clearance", None) is not None:
            if any(abs(k - 1) > 2 * CLEARANCE * (1 + 1e-9) for k in pl.clearance):
                bad.append(f"a clearance of {pl.clearance} on an exported {pl.kind}, beyond 1 ± {2 * CLEARANCE}")
            band |= pl.inside(pts) != pl.inside_own(pts)
    want = tree_inside(sc.root, pts)
    got = sdl["root"].inside(pts) if sdl["root"] else np.zeros(len(pts), dtype=bool)
    if np.any((want != got) & ~band):
        bad.append(f"the exported solid differs at {int(np.sum((want != got) & ~band))} of {len(pts)} points")
    # The solids csgrt may export for each leaf: the leaf, or for an
    # extrusion each solid one of its 2-D leaves sweeps.
    mine = []
    for x in sc.leaves:
        if x.kind in reader.EXTRUSIONS:
            q = (pts - x.matrix[:3, 3]) @ np.linalg.inv(x.matrix[:3, :3]).T
            mine += [(x, part) for part in extrusion_parts(x, q)[1]]
        else:
            mine.append((x, leaf_inside(x, pts)))
    for pl in pov_leaves(sdl["root"]):
        ins = pl.inside_own(pts) if isinstance(pl, PovLeaf) else pl.inside(pts)
        match = [x for x, part in mine if np.array_equal(part, ins)]
        if not match:
            bad.append(f"an exported {pl.kind} is no solid of the file")
            continue
        # Solids that sample alike (a thin one no point falls in): any of
        # them with the exported texture will do.
        problems = [texture_problems(pl, x.material) for x in match]
        if all(problems):
            bad += problems[0]
    return bad


def checked(job):
    """(scene, its problems): `check`, a scene it cannot read a problem."""
    path, csgrt = job
    try:
        return path, check(path, csgrt)
    except (ValueError, KeyError, subprocess.CalledProcessError, reader.ReadError) as e:
        return path, [f"cannot check: {e}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--csgrt", default="target/release/csgrt")
    a = ap.parse_args()
    failed = 0
    # The scenes two (or as many as there are cores) at once, reported in
    # the order given.
    with multiprocessing.get_context("fork").Pool(os.cpu_count() or 1) as pool:
        for path, bad in pool.imap(checked, [(p, a.csgrt) for p in a.scenes]):
            name = os.path.basename(path)
            print(f"{name}: {'ok' if not bad else bad[0]}", flush=True)
            for b in bad[1:5]:
                print(f"  {b}")
            failed += bool(bad)
    print(f"{len(a.scenes) - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
