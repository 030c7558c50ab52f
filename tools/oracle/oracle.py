#!/usr/bin/env python3
"""The manifold3d oracle: does csgrt render what the file says?

For each scene the oracle reads the file itself (tools/oracle/scene/, its own
parser, sharing nothing with csgrt's Rust code), builds the same CSG tree
with manifold3d at several numbers of circular segments n, takes its own
camera, and compares with what csgrt outputs: the image and the hit mask of
a render at one sample a pixel, and `--trace-rays` answers (t and normal)
for the ray through every pixel centre of the oracle's camera plus a set of
random rays (seeded by the scene's file name) from all around the solid.

What is compared, everything in the verdict:

* hit/miss per pixel (csgrt's mask against the oracle's cast through the
  oracle's camera) and per ray;
* depth: |t_csgrt - t_mesh| within the depth bound (below) at every pixel
  and every ray, at every angle of incidence;
* normals: the angle between csgrt's normal and the mesh's within the
  normal bound (below);
* colour: every pixel whose surface is opaque and not reflective is shaded
  by the oracle with the seed's Phong model (slides 25-29: ka Ia C, then
  per light kd (N.L) C Il + ks (V.R)^ns Il, shadows from the mesh, the
  light dimmed by the kt of transparent blockers, each channel clamped and
  rounded to a byte) from the oracle's own materials and lights and csgrt's
  (already checked) hit point and normal; it must match csgrt's byte within
  2 levels. Where a light's shadow is ambiguous (the pixel's 3x3 neighbours
  disagree about it in the oracle, or N.L < 0.02) both answers are accepted.

A pixel can only disagree where the picture has an edge: the oracle's 3x3
neighbourhood holds a hit and a miss, or two surfaces (two leaves, or two
faces of one leaf: a cube's sides, a cylinder's caps and side). Every
disagreeing pixel must be such an edge pixel, at every n; and the number of
disagreeing pixels and rays must not grow as n doubles (within 2 of grid
noise) and must shrink overall from the coarsest n to the finest, unless
it is already 2 or less. At the finest n, no random ray may be beyond its
depth or normal bound.

The bounds (per leaf, for the leaf the mesh ray hits; b = 1 - cos(pi/n)):

* faceting distance delta: the mesh lies within delta of the true surface,
  delta = k R b sigma_max (R the leaf's largest radius, sigma_max the
  largest singular value of its matrix; k = 1 for a cylinder or cone, whose
  mesh is an inscribed polygon; 3 for manifold's geodesic sphere, measured
  2.69; a torus adds its tube's and its sweep's bounds; cubes and
  halfspaces are exact, delta = 0);
* depth: a ray meeting the surface at angle theta (c = |cos theta|, from
  csgrt's normal) sees that offset as at most delta / c, and a surface of
  curvature radius R_c moved inward by delta is met at most sqrt(2 R_c
  delta) away even at grazing (the chord of the sphere of radius R_c), so

      |t_csgrt - t_mesh| <= min(2 delta / c, 2 sqrt(2 R delta)) + 1e-9 L

  (a factor 2 for the first-order estimates, L = |origin| + t the ray's
  length scale); the bound grows toward grazing and stays finite there;
* normal: a face whose vertices lie on the surface turns from the true
  normal by at most the facet angle: pi/n for a cylinder's or cone's side
  (the face spans 2 pi/n of azimuth, the normal at its middle), for the
  sphere the angular radius of the face, acos(1 - 3 b) (its plane lies
  within 3 b R), for a torus pi/n of sweep plus pi/n of tube. A linear map
  turns angles by at most its condition number kappa = sigma_max /
  sigma_min. The two normals are taken at two points of the surface: the
  exact hit and the mesh's, |t_csgrt - t_mesh| apart along the ray and
  within delta of the surface, so the true normal itself turns by at most
  (|dt| + delta) / rho between them, rho the world's smallest curvature
  radius there (sigma_min r / kappa for an object radius r: the sphere's
  r, the cone's radius at the hit, the torus's min(r, R - r)). Hence

      angle <= kappa * facet(n) + kappa (|dt| + delta) / (sigma_min r) + 1e-7.

A halfspace is unbounded; the mesh stands it in by a box 10^6 times the
scene's size, whose far faces lie far below one pixel from the horizon.

Usage: oracle.py [--csgrt BIN] [--size WxH] [--segments 64,128,256,512]
                 [--rays N] [--out DIR] [--check] [--table FILE] SCENE...
Exit status 1 when --check finds a scene that fails.
"""

import argparse
import itertools
import hashlib
import math
import multiprocessing
import os
import subprocess
import sys
import tempfile
import time

import manifold3d as mf
import numpy as np
from PIL import Image

from tools.oracle import scene as reader  # noqa: E402  (the oracle's own reader)

SPHERE_FACTOR = 3.0  # measured 2.69, rounded up
GROW_SLACK = 2  # pixels or rays of grid noise allowed when n doubles
COLOUR_TOLERANCE = 2  # bytes
FP_ANGLE = 1e-7  # radians


def seed_of(name):
    return int(hashlib.sha256(name.encode()).hexdigest()[:8], 16)


# --------------------------------------------------------------------------
# The leaves: meshes, bounds, faces
# --------------------------------------------------------------------------


def svd(leaf):
    """The largest and smallest singular values of the leaf's matrix,
    computed once a leaf (they are asked for at every ray)."""
    if not hasattr(leaf, "_svd"):
        s = np.linalg.svd(leaf.matrix[:3, :3], compute_uv=False)
        leaf._svd = (float(s[0]), float(s[-1]))
    return leaf._svd


def curve_steps(n):
    """The pieces a quadratic or cubic edge is cut into at n circle
    segments."""
    return max(2, n // 16)


def flatten_curves(f, n):
    """A curves leaf as polygons: each curve cut into equal steps of its
    parameter, the points on the curve (the chords inscribed)."""
    m = curve_steps(n)
    u = np.arange(m) / m
    loops = []
    for l in f[1]:
        pts = []
        for i, (a, c) in enumerate(l):
            if c is None:
                pts.append(a[None, :])
            else:
                b = l[(i + 1) % len(l)][0]
                pts.append(reader.bezier_eval(reader.bezier_points(a, c, b), u))
        loops.append(np.concatenate(pts))
    return loops


def arc_sweep(a, arc, b):
    """(centre, radius, start angle, sweep) of a drawing's arc from a to b
    through its middle point (either way round)."""
    c, r, mid = arc
    a0 = math.atan2(a[1] - c[1], a[0] - c[0])
    am = math.atan2(mid[1] - c[1], mid[0] - c[0])
    a1 = math.atan2(b[1] - c[1], b[0] - c[0])
    ccw = (am - a0) % (2 * math.pi) < (a1 - a0) % (2 * math.pi) or abs(a1 - a0) < 1e-15
    sweep = (a1 - a0) % (2 * math.pi) if ccw else -((a0 - a1) % (2 * math.pi))
    return c, r, a0, sweep if sweep != 0 else 2 * math.pi


class Line:
    """The straight piece a + u (b - a), u in [0, 1]."""

    def __init__(self, a, b):
        self.a, self.b = np.asarray(a, float), np.asarray(b, float)
        self.first = self.a

    def __call__(self, u):
        u = np.asarray(u, float)
        return self.a + u[..., None] * (self.b - self.a) if u.ndim else self.a + u * (self.b - self.a)

    def d(self, u):
        return np.broadcast_to(self.b - self.a, np.shape(u) + (2,))

    def reach(self):
        return max(float(np.linalg.norm(self.a)), float(np.linalg.norm(self.b)))


class Arc:
    """The piece c + A (cos w, sin w) of an ellipse, w from w0 over dw;
    its ends lie on the ellipse, as the inscribed polygon's vertices do."""

    def __init__(self, A, c, w0, dw, first=None):
        self.A, self.c, self.w0, self.dw = np.asarray(A, float), np.asarray(c, float), w0, dw
        # The loop's vertex where the piece starts: the path's own point
        # where it has one.
        self.first = self(0.0) if first is None else np.asarray(first, float)

    def __call__(self, u):
        w = self.w0 + np.asarray(u, float) * self.dw
        return self.c + np.stack([np.cos(w), np.sin(w)], axis=-1) @ self.A.T

    def d(self, u):
        w = self.w0 + np.asarray(u, float) * self.dw
        return self.dw * np.stack([-np.sin(w), np.cos(w)], axis=-1) @ self.A.T

    def reach(self):
        return float(np.linalg.norm(self.c)) + float(np.linalg.svd(self.A, compute_uv=False)[0])


def circle_pieces(A, c, n):
    """An ellipse's n pieces, between the vertices of manifold's n-gon."""
    return [Arc(A, c, 2 * math.pi * i / n, 2 * math.pi / n) for i in range(n)]


def drawing_pieces(f, n):
    """A drawing's loops as pieces: its paths' lines and arcs (cut into
    steps of at most 2 pi / n), then its circles."""
    _, paths, circles = f[3]
    loops = []
    for path in paths:
        pieces = []
        for i, (a, arc) in enumerate(path):
            b = path[(i + 1) % len(path)][0]
            if arc is None:
                pieces.append(Line(a, b))
                continue
            c, r, a0, sweep = arc_sweep(a, arc, b)
            k = max(1, math.ceil(abs(sweep) / (2 * math.pi / n)))
            pieces += [Arc(r * np.eye(2), c, a0 + sweep * j / k, sweep / k, a if j == 0 else None) for j in range(k)]
        loops.append(pieces)
    for c, r in circles:
        loops.append(circle_pieces(r * np.eye(2), c, n))
    return loops


def section_pieces(f, n):
    """The pieces of every edge a 2-D tree's cross-section is cut from at n
    (polygons' edges, circles' and arcs' steps), for the twisted bounds."""
    if f[0] == "poly":
        return [Line(l[i], l[(i + 1) % len(l)]) for l in f[1] for i in range(len(l))]
    if f[0] == "ellipse":
        return circle_pieces(f[1], f[2], n)
    if f[0] == "op" and len(f) == 4 and f[3][0] == "drawing":
        return [g for loop in drawing_pieces(f, n) for g in loop]
    if f[0] == "op" and f[1] == "hull":
        loops = cross_section(f, n).to_polygons()
        return [Line(np.array(l[i]), np.array(l[(i + 1) % len(l)])) for l in loops for i in range(len(l))]
    if f[0] == "op":
        return [g for k in f[2] for g in section_pieces(k, n)]
    return []


def has_hull(f):
    """Whether a 2-D tree holds a hull or an offset (whose edges exist only
    once manifold has made it)."""
    offset = len(f) == 4 and f[3][0] in ("round", "miter", "square", "sum")
    return f[0] == "op" and (f[1] == "hull" or offset or any(has_hull(k) for k in f[2]))


def svg_loop_points(x, n):
    """An SVG loop cut up at n: lines as they are, curves in curve_steps(n)
    steps, arcs in steps of at most 2 pi / n (inscribed)."""
    _, pts, segs = x
    out = []
    for i, sg in enumerate(segs):
        a, b = pts[i], pts[(i + 1) % len(pts)]
        if sg is None:
            out.append(a)
        elif sg[0] == "A":
            out += reader.svg_arc_steps(sg[1], sg[2], a, b, sg[3], 2 * math.pi / n)
        else:
            m = curve_steps(n)
            P = reader.bezier_points(a, sg[1] if sg[0] == "Q" else np.array(sg[1:3]), b)
            out += list(reader.bezier_eval(P, np.arange(m) / m))
    return np.array(out)


def cross_section(f, n):
    """manifold's cross-section of a 2-D tree of scene.py (circles as
    n-gons inscribed in them, quadratic edges as inscribed polylines)."""
    if f[0] == "curves":
        return mf.CrossSection([l.tolist() for l in flatten_curves(f, n)], mf.FillRule.EvenOdd)
    if f[0] == "poly":
        return mf.CrossSection([l.tolist() for l in f[1]], mf.FillRule.EvenOdd)
    if f[0] == "faces":
        # A shadow: the union of its faces' (each counter-clockwise).
        return mf.CrossSection([l.tolist() for l in f[1]], mf.FillRule.Positive)
    if f[0] == "ellipse":
        A, c = f[1], f[2]
        return mf.CrossSection.circle(1.0, n).transform([[A[0, 0], A[0, 1], c[0]], [A[1, 0], A[1, 1], c[1]]])
    if len(f) == 4 and f[3][0] == "svg":
        # Each element's loops (curves and arcs cut up, ellipses as n-gons,
        # strokes as Clipper made them) even-odd; the elements united.
        shapes = []
        for _, parts, _ in f[3][1]:
            loops = []
            for x in parts:
                if x[0] == "polys":
                    loops += list(x[1])
                elif x[0] == "ellipse":
                    ang = 2 * math.pi * np.arange(n) / n
                    loops.append(np.column_stack([np.cos(ang), np.sin(ang)]) @ x[1].T + x[2])
                else:
                    loops.append(svg_loop_points(x, n))
            shapes.append(mf.CrossSection([l.tolist() for l in loops if len(l) >= 3], mf.FillRule.EvenOdd))
        return mf.CrossSection.batch_boolean(shapes, mf.OpType.Add)
    if len(f) == 4 and f[3][0] == "drawing":
        # A drawing: its own paths, arcs cut into steps of at most 2 pi / n
        # (inscribed), and its circles, filled even-odd.
        loops = [np.array([g.first for g in path]) for path in drawing_pieces(f, n)]
        return mf.CrossSection([l.tolist() for l in loops if len(l) >= 3], mf.FillRule.EvenOdd)
    if len(f) == 4 and f[3][0] == "sum":
        # A polygon plus a convex polygon: the union of the hulls of its
        # triangles' (manifold's triangulation) corners plus B's, moved.
        _, b, child, m = f[3]
        polys = [np.asarray(l, dtype=float) for l in cross_section(child, n).to_polygons()]
        pts = np.concatenate(polys)
        tris = [pts[t] for t in np.asarray(mf.triangulate([p.tolist() for p in polys]))]
        cs = mf.CrossSection.batch_boolean(
            [mf.CrossSection.hull_points((t[:, None, :] + b[None, :, :]).reshape(-1, 2).tolist()) for t in tris], mf.OpType.Add
        )
        return cs.transform([[m[0, 0], m[0, 1], m[0, 2]], [m[1, 0], m[1, 1], m[1, 2]]])
    if len(f) == 4 and f[3][0] == "kites":
        return mf.CrossSection.batch_boolean([cross_section(k, n) for k in f[2]], mf.OpType.Add)
    if len(f) == 4:
        # An offset: manifold's own (Clipper2's) of the child, then moved.
        join, d, child, m = f[3]
        jt = {"round": mf.JoinType.Round, "miter": mf.JoinType.Miter, "square": mf.JoinType.Square}[join]
        cs = cross_section(child, n).offset(d, jt, 1e6, n)
        return cs.transform([[m[0, 0], m[0, 1], m[0, 2]], [m[1, 0], m[1, 1], m[1, 2]]])
    kids = [cross_section(k, n) for k in f[2]]
    if f[1] == "union":
        return mf.CrossSection.batch_boolean(kids, mf.OpType.Add)
    if f[1] == "hull":
        return mf.CrossSection.batch_hull(kids)
    if f[1] == "xor":
        acc = kids[0]
        for k in kids[1:]:
            acc = (acc - k) + (k - acc)
        return acc
    if f[1] == "intersection":
        return mf.CrossSection.batch_boolean(kids, mf.OpType.Intersect)
    return kids[0] - mf.CrossSection.batch_boolean(kids[1:], mf.OpType.Add)


def twist_steps(leaf, n):
    """(slices, pieces a polygon edge is cut into) of a twisted or unevenly
    scaled extrusion's mesh at n: slices turning at most 2 pi / n each (at
    least n / 8), edges cut so that the ruled sides' triangles converge."""
    th = abs(math.radians(leaf.params["twist"]))
    return max(n // 8, int(math.ceil(th * n / (2 * math.pi)))), max(2, n // 16)


def refined(f, m):
    """A 2-D tree with each straight edge (of a polygon or a drawing's
    path) cut into m equal pieces."""
    if f[0] == "poly":
        u = np.arange(m)[:, None] / m
        return ("poly", [np.concatenate([(1 - u) * l[i] + u * l[(i + 1) % len(l)] for i in range(len(l))]) for l in f[1]])
    if f[0] == "op" and len(f) == 4 and f[3][0] == "drawing":
        _, paths, circles = f[3]
        cut = []
        for path in paths:
            out = []
            for i, (a, arc) in enumerate(path):
                out.append((a, arc))
                if arc is None:
                    b = path[(i + 1) % len(path)][0]
                    out += [((1 - j / m) * a + j / m * b, None) for j in range(1, m)]
            cut.append(out)
        return ("op", f[1], [refined(k, m) for k in f[2]], ("drawing", cut, circles))
    if f[0] == "op":
        return ("op", f[1], [refined(k, m) for k in f[2]]) + tuple(f[3:])
    return f


def extrusion_mesh(leaf, n):
    p = leaf.params
    if leaf.kind == "linear_extrude" and reader.twisted(p):
        slices, m = twist_steps(leaf, n)
        if has_hull(p["flat"]):
            # A hull's tangent edges (an offset's edges) exist only once it
            # is made: cut them (and every other edge) after.
            loops = [np.array(l) for l in cross_section(p["flat"], n).to_polygons()]
            cs = mf.CrossSection([l.tolist() for l in refined(("poly", loops), m)[1]], mf.FillRule.Positive)
        else:
            cs = cross_section(refined(p["flat"], m), n)
        # manifold turns counter-clockwise, OpenSCAD clockwise; both scale
        # after turning (S R p).
        mesh = mf.Manifold.extrude(cs, p["h"], slices - 1, -p["twist"], tuple(p["scale2"]))
        return mesh.translate([0.0, 0.0, p["z0"]])
    if leaf.kind == "linear_extrude":
        cs = cross_section(p["flat"], n)
        m = mf.Manifold.extrude(cs, p["h"], 0, 0.0, (p["scale"], p["scale"]))
        return m.translate([0.0, 0.0, p["z0"]])
    f, flip = reader.revolve_setup(p)
    cs = cross_section(f, n)
    angle = p["angle"]
    segs = max(3, int(math.ceil(n * abs(angle) / 360.0)))
    m = mf.Manifold.revolve(cs, segs, abs(angle))
    if angle < 0:
        m = m.mirror([0.0, 1.0, 0.0])
    if flip:
        m = m.rotate([0.0, 0.0, 180.0])
    return m


def polyhedron_triangles(p):
    """The oracle's own triangulation of a polyhedron's faces (manifold's
    polygon triangulator, each face projected across its Newell normal),
    turned counter-clockwise seen from outside (OpenSCAD lists faces
    clockwise)."""
    pts = p["points"]
    tris = []
    for f in p["faces"]:
        q = pts[f]
        nrm = np.zeros(3)
        for i in range(len(f)):
            a, b = q[i], q[(i + 1) % len(f)]
            nrm += [(a[1] - b[1]) * (a[2] + b[2]), (a[2] - b[2]) * (a[0] + b[0]), (a[0] - b[0]) * (a[1] + b[1])]
        k = int(np.argmax(np.abs(nrm)))
        i, j = [(1, 2), (2, 0), (0, 1)][k]
        flat = q[:, [i, j]]
        if nrm[k] < 0:
            flat = flat * [1.0, -1.0]
        for t in np.asarray(mf.triangulate([flat.tolist()])):
            tris.append([f[t[0]], f[t[2]], f[t[1]]])
    tris = np.array(tris, dtype=np.uint32)
    # A solid whatever its winding (csgrt's parity rule): turned outward
    # when its signed volume is negative.
    a, b, c = pts[tris[:, 0]], pts[tris[:, 1]], pts[tris[:, 2]]
    if np.einsum("ij,ij->i", a, np.cross(b, c)).sum() < 0:
        tris = tris[:, [0, 2, 1]]
    return tris


def polyhedron_solid(leaf):
    """manifold3d's solid of a polyhedron leaf in its object space (the
    oracle's own triangulation, kept on the leaf)."""
    if not hasattr(leaf, "_solid"):
        tris = polyhedron_triangles(leaf.params)
        m = mf.Manifold(mf.Mesh64(vert_properties=np.asarray(leaf.params["points"], dtype=np.float64), tri_verts=tris))
        if m.status() != mf.Error.NoError or m.is_empty():
            raise ValueError(f"the oracle's manifold3d cannot take this polyhedron: {m.status()}")
        leaf._solid = m
    return leaf._solid


def convex_solid(m):
    """Whether a mesh is convex: its volume is its hull's."""
    hv = m.hull().volume()
    return abs(hv - m.volume()) <= 1e-9 * max(hv, 1e-300)


def leaf_mesh(leaf, n, big):
    p = leaf.params
    k = leaf.kind
    if k == "hull":
        return mf.Manifold.batch_hull([leaf_mesh(x, n, big) for x in p["parts"]]).as_original()
    if k == "minkowski":
        ops = [[(m, convex_solid(m)) for m in (leaf_mesh(x, n, big) for x in o)] for o in p["operands"]]
        # The sum distributes over each operand's union: each choice of
        # one leaf from each operand summed, then united. Convex leaves sum
        # to the hull of their vertices' sums (robust where manifold's
        # general sum leaves slivers at some resolutions); the others by
        # manifold's minkowski_sum.
        pieces = []
        for combo in itertools.product(*ops):
            convex = [m for m, c in combo if c]
            acc = None
            if convex:
                pts = convex[0].to_mesh().vert_properties[:, :3]
                for m in convex[1:]:
                    q = m.to_mesh().vert_properties[:, :3]
                    pts = mf.Manifold.hull_points((pts[:, None, :] + q[None, :, :]).reshape(-1, 3)).to_mesh().vert_properties[:, :3]
                acc = mf.Manifold.hull_points(pts)
            for m in [m for m, c in combo if not c]:
                # (the mesh that is not convex first, as manifold is fast)
                acc = m if acc is None else m.minkowski_sum(acc)
            pieces.append(acc)
        return mf.Manifold.batch_boolean(pieces, mf.OpType.Add).as_original()
    if k == "polyhedron":
        return polyhedron_solid(leaf).transform(leaf.matrix[:3, :].tolist()).as_original()
    if k in reader.EXTRUSIONS:
        return extrusion_mesh(leaf, n).transform(leaf.matrix[:3, :].tolist()).as_original()
    if k == "sphere":
        m = mf.Manifold.sphere(p["r"], n)
    elif k == "cube":
        m = mf.Manifold.cube(p["size"].tolist(), p["center"])
    elif k == "cylinder":
        m = mf.Manifold.cylinder(p["h"], p["r1"], p["r2"], n, p["center"])
    elif k == "torus":
        m = mf.CrossSection.circle(p["r"], n).translate([p["R"], 0.0]).revolve(n)
    else:
        nrm = p["normal"] / np.linalg.norm(p["normal"])
        off = p["offset"] / np.linalg.norm(p["normal"])
        z = nrm
        helper = np.array([1.0, 0, 0]) if abs(z[0]) < 0.9 else np.array([0, 1.0, 0])
        x = np.cross(helper, z)
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        frame = np.eye(4)
        frame[:3, :3] = np.column_stack([x, y, z])
        frame[:3, 3] = z * off
        m = mf.Manifold.cube([2 * big, 2 * big, big], True).translate([0.0, 0.0, -big / 2])
        m = m.transform(frame[:3, :].tolist())
    return m.transform(leaf.matrix[:3, :].tolist()).as_original()


def ellipses(f):
    """The ellipses (A, c) of a 2-D tree."""
    if f[0] == "ellipse":
        return [(f[1], f[2])]
    if f[0] in ("poly", "curves", "faces"):
        return []
    return [e for k in f[2] for e in ellipses(k)]


def flat_extent(f):
    """The largest |coordinate| of a 2-D tree's leaves."""
    if f[0] == "faces":
        # (thousands of loops: once a shadow)
        if id(f) not in SHADOW_EXTENT:
            SHADOW_EXTENT[id(f)] = (f, float(np.abs(np.concatenate(f[1])).max()))
        return SHADOW_EXTENT[id(f)][1]
    if f[0] == "poly":
        return float(max(np.abs(l).max() for l in f[1]))
    if f[0] == "curves":
        return float(np.abs(np.array(reader.curve_extent(f))).max())
    if f[0] == "ellipse":
        return float(np.abs(f[2]).max() + np.linalg.norm(f[1], 2))
    return max(flat_extent(k) for k in f[2])


# manifold3d's CrossSection stores points on a grid of 1e-8 (Clipper2's
# eight decimals: 0.1234567891234 comes back as 0.12345679104): every vertex
# of the oracle's own 2-D shapes moves by up to this much in the plane.
CROSS_SECTION_GRID = 1e-8


def extrusion_facets(leaf, n):
    """(distance, angle) of an extrusion's mesh at n segments: circles are
    inscribed n-gons (an ellipse's distance and angle grow with its
    matrix's singular values and condition); a turn is cut in n steps
    about the axis, within R (1 - cos(pi/n)) of the surface at distance R,
    its normals within pi/n, doubled where a circle's facets add their
    own. Computed once a leaf and n."""
    cache = leaf.__dict__.setdefault("_extrusion_facets", {})
    if n not in cache:
        cache[n] = extrusion_facets_of(leaf, n)
    return cache[n]


def extrusion_facets_of(leaf, n):
    p = leaf.params
    b = 1 - math.cos(math.pi / n)
    sv = ellipse_singular_values(leaf)
    if leaf.kind == "linear_extrude" and reader.twisted(p):
        d, a = twisted_facets(leaf, n)[:2]
        return d + CROSS_SECTION_GRID * max([1.0] + list(p["scale2"])), a
    if leaf.kind == "linear_extrude":
        k = max(1.0, p["scale"])
        qd, qa = quad_facets(leaf, n)
        sd, sa = svg_slack(p["flat"])
        dist = max(max((s[0] * k * b for s in sv), default=0.0), qd * k) + (CROSS_SECTION_GRID + sd) * k
        bk, sharp = bands(p["flat"])
        if bk:
            # A curved outline offset: the flattened outline's distance and
            # the offset's arcs add (an offset moves by no more than its
            # outline); Clipper's miters and squares at the flattened
            # outline's corners (turning by at most 2 qa) stand off the
            # round offset by up to |d| (1 / cos(qa) - 1).
            dist += qd * k + (bk * (1 / math.cos(min(qa, 1.0)) - 1) * k if sharp else 0.0)
        dist += kite_reach(p["flat"]) * math.pi / n * k
        ang = max(max((s[0] / s[1] * math.pi / n for s in sv), default=0.0), qa) + sa
        return dist, ang
    R = flat_extent(p["flat"])
    emax = max((s[0] for s in sv), default=0.0)
    qd, qa = quad_facets(leaf, n)
    sd, sa = svg_slack(p["flat"])
    dist = (R + emax) * b + max(emax * b, qd) + CROSS_SECTION_GRID + sd + kite_reach(p["flat"]) * math.pi / n
    ang = (2 if sv or qa else 1) * math.pi / n * max((s[0] / s[1] for s in sv), default=1.0) + qa + sa
    return dist, ang


def svg_slack(f):
    """(distance, angle) by which an SVG drawing's strokes in a 2-D tree,
    as Clipper makes them, may stand off the exact ones (scene.py's
    svg_stroke_slack, carried by each element's transform: distances by
    its largest singular value, angles by its condition number)."""
    if f[0] != "op":
        return 0.0, 0.0
    if len(f) == 4 and f[3][0] == "svg":
        dist = ang = 0.0
        for m, _, (d, a) in f[3][1]:
            sv_ = np.linalg.svd(m[:2, :2], compute_uv=False)
            dist, ang = max(dist, d * float(sv_[0])), max(ang, a * float(sv_[0] / sv_[1]))
        return dist, ang
    rs = [svg_slack(k) for k in f[2]]
    return max(r[0] for r in rs), max(r[1] for r in rs)


def twist_surface(p, g, u, t):
    """Points X and unit normals N of a twisted side, over the section's
    piece g (a Line or an Arc) at parameter u and height fraction t
    (arrays), in the extrusion's own coordinates: X = (S(t) R(-theta t)
    g(u), z0 + h t), N along X_u x X_t."""
    th = math.radians(p["twist"])
    sx, sy = p["scale2"]
    sg = np.stack([1 + (sx - 1) * t, 1 + (sy - 1) * t], axis=-1)
    ang = -th * t
    c, s_ = np.cos(ang), np.sin(ang)
    q, e = g(u), g.d(u)
    rq = np.stack([c * q[..., 0] - s_ * q[..., 1], s_ * q[..., 0] + c * q[..., 1]], axis=-1)
    re = np.stack([c * e[..., 0] - s_ * e[..., 1], s_ * e[..., 0] + c * e[..., 1]], axis=-1)
    # d/dt of R(-theta t) q is -theta R(-theta t + pi/2) q.
    drq = -th * np.stack([-rq[..., 1], rq[..., 0]], axis=-1)
    xu = np.concatenate([sg * re, np.zeros(u.shape + (1,))], axis=-1)
    xt = np.concatenate([np.array([sx - 1, sy - 1]) * rq + sg * drq, np.full(u.shape + (1,), p["h"])], axis=-1)
    X = np.concatenate([sg * rq, (p["z0"] + p["h"] * t)[..., None]], axis=-1)
    N = np.cross(xu, xt)
    with np.errstate(divide="ignore", invalid="ignore"):
        # (none where a pyramid's section has shrunk to its apex)
        return X, N / np.linalg.norm(N, axis=-1, keepdims=True)


def twisted_facets(leaf, n):
    """(distance, angle, curvature radius) of a twisted extrusion's mesh
    at n, computed once a leaf and n. Distance, derived: the mesh's
    vertices lie on the surface X(u, t) = S(t) R(-theta t) g(u) over the
    section's pieces g (straight edges cut in m, circles' and arcs' steps
    of at most 2 pi / n, whose ends lie on the curve); between slices
    Delta t apart it departs from its chords by at most Delta t^2 / 8
    max|X_tt| <= Delta t^2 rho (2 k theta + s theta^2) / 8 (rho the
    farthest point of the section, k = max|s_i - 1|, s = max(1, s_i)), and
    a cell's bilinear patch from its two triangles by a quarter of its
    twist |(M(t1) - M(t0)) e| <= Delta t (k + s theta) l (l the longest
    chord of a piece); a circle or arc adds its inscribed polygon's r b s.
    Angle and curvature radius, sampled: the largest angle between the
    true surface's normal at each cell's corners and middle (on the curve
    itself for a circle's or arc's step) and the normals of the cell's
    triangles (either diagonal), and the smallest ratio of distance to
    normal turn between neighbouring samples, each with a factor 2 of
    margin."""
    cache = leaf.__dict__.setdefault("_twisted_facets", {})
    if n in cache:
        return cache[n]
    p = leaf.params
    slices, m = twist_steps(leaf, n)
    th = abs(math.radians(p["twist"]))
    sx, sy = p["scale2"]
    k, sg = max(abs(sx - 1), abs(sy - 1)), max(1.0, sx, sy)
    dt = 1.0 / slices
    pieces = section_pieces(refined(p["flat"], m), n)
    sv = ellipse_singular_values(leaf)
    radii = [s[0] for s in sv]
    rho = max([g.reach() for g in pieces] + [0.0])
    piece = max([float(np.linalg.norm(g(1.0) - g(0.0))) for g in pieces] + [0.0])
    bcirc = 1 - math.cos(math.pi / n)
    dist = dt * dt * rho * (2 * k * th + sg * th * th) / 8 + dt * (k + sg * th) * piece / 4
    dist += max((r * bcirc * sg for r in radii), default=0.0) + kite_reach(p["flat"]) * math.pi / n * sg
    ang, curv = 0.0, math.inf
    t = np.linspace(0.0, 1.0, slices + 1)
    uu, tt = np.meshgrid(np.array([0.0, 0.5, 1.0]), np.concatenate([t, (t[:-1] + t[1:]) / 2]))
    for g in pieces:
        X, N = twist_surface(p, g, uu, tt)
        corner = X[: slices + 1]
        c00, c10 = corner[:-1, 0], corner[:-1, 2]
        c01, c11 = corner[1:, 0], corner[1:, 2]
        tri = [np.cross(c10 - c00, c11 - c00), np.cross(c11 - c00, c01 - c00), np.cross(c10 - c00, c01 - c00), np.cross(c11 - c10, c01 - c10)]
        with np.errstate(divide="ignore", invalid="ignore"):
            # (a cell shrunk to a point, at a pyramid's apex, has none)
            tri = [f / np.linalg.norm(f, axis=-1, keepdims=True) for f in tri]
        Nc = N[: slices + 1]
        samples = [Nc[:-1, 0], Nc[:-1, 2], Nc[1:, 0], Nc[1:, 2], N[slices + 1 :, 1]]
        if isinstance(g, Arc):
            # A curved piece bulges from its chord most at its middle.
            samples += [Nc[:-1, 1], Nc[1:, 1]]
        for f in tri:
            for s_ in samples:
                cosv = np.abs(np.sum(f * s_, axis=-1)).clip(0, 1)
                ok = np.isfinite(cosv)
                if ok.any():
                    ang = max(ang, float(np.arccos(cosv[ok]).max()))
        # Curvature: normal turn against distance along t and along u.
        for (X1, N1, X2, N2) in ((X[:slices, 0], Nc[:-1, 0], X[1 : slices + 1, 0], Nc[1:, 0]), (X[: slices + 1, 0], Nc[:, 0], X[: slices + 1, 2], Nc[:, 2])):
            turn = np.arccos(np.abs(np.sum(N1 * N2, axis=-1)).clip(0, 1))
            dd = np.linalg.norm(X2 - X1, axis=-1)
            with np.errstate(divide="ignore", invalid="ignore"):
                r = np.where(turn > 0, dd / turn, np.inf)
            r = r[np.isfinite(turn)]
            if r.size:
                curv = min(curv, float(r.min()) / 2)
    circ = max((s[0] / s[1] * math.pi / n for s in sv), default=0.0)
    cache[n] = (dist, max(2 * ang, circ), min(curv, min((s[1] * min(1.0, sx, sy) for s in sv), default=math.inf)))
    return cache[n]


def quads(f):
    """The curved edges of a 2-D tree, each as its control points (3 for a
    quadratic, 4 for a cubic)."""
    if f[0] == "curves":
        return [reader.bezier_points(*e) for e in reader.curve_pieces(f) if e[1] is not None]
    if f[0] in ("poly", "ellipse", "faces"):
        return []
    return [e for k in f[2] for e in quads(k)]


def quad_facets(leaf, n):
    """(distance, angle) of the inscribed polylines of the leaf's curved
    edges at n. Distance: over a parameter step h = 1/m a curve is within
    h^2 / 8 max|B''| of its chord; B'' is constant for a quadratic,
    2 (a - 2c + b), and linear for a cubic, 6 (a - 2c1 + c2) to
    6 (c1 - 2c2 + b), largest at an end. Angle: somewhere in its step the
    curve is parallel to its chord (Rolle's theorem on the distance from
    the chord's line), so the chord's normal is within the range of the
    tangent's direction over the step of the curve's: for a quadratic
    (which turns one way) the angle between the step's end tangents; for a
    cubic that range sampled at 9 points a step, with a factor 2 of
    margin. Computed once a leaf and n."""
    cache = leaf.__dict__.setdefault("_quad_facets", {})
    if n not in cache:
        m = curve_steps(n)
        dist = ang = 0.0
        for P in quads(leaf.params["flat"]):
            k = len(P) - 1
            dd = [k * (k - 1) * float(np.linalg.norm(P[i] - 2 * P[i + 1] + P[i + 2])) for i in range(k - 1)]
            dist = max(dist, max(dd) / (8 * m * m))
            sub = 1 if k == 2 else 8
            u = np.arange(m * sub + 1) / (m * sub)
            D = k * sum(math.comb(k - 1, i) * (1 - u[:, None]) ** (k - 1 - i) * u[:, None] ** i * (P[i + 1] - P[i]) for i in range(k))
            rel = np.arctan2(D[:, 1], D[:, 0])
            for j in range(m):
                w = np.unwrap(rel[j * sub : (j + 1) * sub + 1])
                ang = max(ang, float(w.max() - w.min()) * (1 if k == 2 else 2))
        cache[n] = (dist, ang)
    return cache[n]


def quad_min_radius(P):
    """The smallest curvature radius |B'|^3 / |B' x B''| of a curved edge:
    for a quadratic B' x B'' is constant, so it is where |B'| is smallest
    (the minimum of a quadratic in u on [0, 1]); for a cubic, sampled at
    257 points, halved for margin."""
    if len(P) == 3:
        a, c, b = P
        p, q = 2 * (c - a), 2 * (b - c)
        k = abs(float(p[0] * q[1] - p[1] * q[0]))
        if k == 0:
            return math.inf
        d = q - p
        u = 0.0 if d @ d == 0 else min(1.0, max(0.0, float(-(p @ d) / (d @ d))))
        v = p + u * d
        return float(np.linalg.norm(v)) ** 3 / k
    u = np.linspace(0.0, 1.0, 257)[:, None]
    d1 = 3 * ((1 - u) ** 2 * (P[1] - P[0]) + 2 * u * (1 - u) * (P[2] - P[1]) + u * u * (P[3] - P[2]))
    d2 = 6 * ((1 - u) * (P[2] - 2 * P[1] + P[0]) + u * (P[3] - 2 * P[2] + P[1]))
    cr = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    with np.errstate(divide="ignore"):
        r = np.where(cr > 0, np.linalg.norm(d1, axis=1) ** 3 / cr, np.inf)
    return float(r.min()) / 2


def ellipse_singular_values(leaf):
    """The singular values of each circle's matrix in the leaf's 2-D tree,
    computed once a leaf."""
    if not hasattr(leaf, "_ellipse_sv"):
        leaf._ellipse_sv = [np.linalg.svd(A, compute_uv=False) for A, _ in ellipses(leaf.params["flat"])]
    return leaf._ellipse_sv


def bands(f):
    """(largest |d|, whether any joins are miter or square) of the curved
    outlines offset in a 2-D tree; (0, False) without."""
    if f[0] != "op":
        return 0.0, False
    parts = [bands(k) for k in f[2]]
    bk = max([x for x, _ in parts] + [f[3][1] if len(f) == 4 and f[3][0] == "bands" else 0.0])
    sharp = any(y for _, y in parts) or bool(bk and len(f) == 4 and f[3][0] in ("miter", "square"))
    return bk, sharp


def kite_reach(f):
    """How far the miter and square joins at the sharp corners of an offset
    of polygons and circles reach from their corners (0 without). Clipper
    joins a flattened circle's last chord, whose direction is within pi / n
    of the circle's tangent at the corner: the kite's side turns by that
    much about the corner, moving its far end by up to reach * pi / n."""
    if f[0] != "op":
        return 0.0
    own = f[3][1] if len(f) == 4 and f[3][0] == "kites" else 0.0
    return max([own] + [kite_reach(k) for k in f[2]])


def extrusion_curvature(leaf):
    """The smallest object-space curvature radius of an extrusion's circles
    (a tapered one's at its smaller end; infinite without circles)."""
    if leaf.kind == "linear_extrude" and reader.twisted(leaf.params):
        return twisted_facets(leaf, 512)[2]
    if not hasattr(leaf, "_curvature"):
        sv = ellipse_singular_values(leaf)
        k = max(leaf.params["scale"], 1e-300) if leaf.kind == "linear_extrude" else 1.0
        r = min((s[1] * k for s in sv), default=math.inf)
        r = min([r] + [quad_min_radius(e) * k for e in quads(leaf.params["flat"])])
        bk = bands(leaf.params["flat"])[0]
        if bk:
            # An offset curve's radius is the edge's plus or minus |d|.
            r = min([r] + [max(quad_min_radius(e) - bk, 1e-300) * k for e in quads(leaf.params["flat"])])
        leaf._curvature = r
    return leaf._curvature


def convex_parts(leaf):
    """A hull's parts, or a Minkowski sum's operands' (lists of leaves)."""
    return [leaf.params["parts"]] if leaf.kind == "hull" else leaf.params["operands"]


def facet_distance(leaf, n):
    if leaf.kind in ("hull", "minkowski"):
        # A hull moves by no more than its parts (the Hausdorff distance of
        # hulls is at most that of the sets), a sum by the sum of its
        # operands'.
        return sum(max(facet_distance(x, n) for x in ops) for ops in convex_parts(leaf))
    p, (smax, _) = leaf.params, svd(leaf)
    b = 1 - math.cos(math.pi / n)
    if leaf.kind in reader.EXTRUSIONS:
        return extrusion_facets(leaf, n)[0] * smax
    if leaf.kind == "sphere":
        return SPHERE_FACTOR * p["r"] * b * smax
    if leaf.kind == "cylinder":
        return max(p["r1"], p["r2"]) * b * smax
    if leaf.kind == "torus":
        return ((p["R"] + p["r"]) * b + p["r"] * b) * smax
    return 0.0


def facet_angle(leaf, n):
    if leaf.kind in ("hull", "minkowski"):
        # A face of the meshed hull (or sum) spans facet vertices of its
        # parts, each within its part's facet angle of the surface there:
        # twice the largest (a sum's, of its operands' summed).
        return 2 * sum(max(facet_angle(x, n) for x in ops) for ops in convex_parts(leaf))
    b = 1 - math.cos(math.pi / n)
    smax, smin = svd(leaf)
    kappa = smax / smin
    if leaf.kind in reader.EXTRUSIONS:
        return kappa * extrusion_facets(leaf, n)[1]
    if leaf.kind == "sphere":
        return kappa * math.acos(max(-1.0, 1 - SPHERE_FACTOR * b))
    if leaf.kind == "cylinder":
        return kappa * math.pi / n
    if leaf.kind == "torus":
        return kappa * 2 * math.pi / n
    return 0.0


def largest_radius(leaf):
    if not hasattr(leaf, "_largest_radius"):
        leaf._largest_radius = largest_radius_of(leaf)
    return leaf._largest_radius


def largest_radius_of(leaf):
    if leaf.kind in ("hull", "minkowski"):
        return sum(max(largest_radius(x) for x in ops) for ops in convex_parts(leaf))
    p, (smax, _) = leaf.params, svd(leaf)
    r = {
        "sphere": lambda: p["r"],
        "cylinder": lambda: max(p["r1"], p["r2"], p["h"]),
        "torus": lambda: p["R"] + p["r"],
        "linear_extrude": lambda: max(flat_extent(p["flat"]) * max([1.0] + list(p.get("scale2") or [p["scale"]])), p["h"]),
        "rotate_extrude": lambda: flat_extent(p["flat"]),
        "polyhedron": lambda: float(np.abs(p["points"]).max()),
    }.get(leaf.kind, lambda: 0.0)()
    return r * smax


def object_point(leaf, x):
    return np.linalg.solve(leaf.matrix[:3, :3], x - leaf.matrix[:3, 3])


def curvature_radius(leaf, x):
    """The smallest object-space curvature radius near world point x."""
    p = leaf.params
    if leaf.kind in ("hull", "minkowski"):
        # No smaller than its parts' smallest (a hull's surface is theirs,
        # or flat or ruled between them; a sum's radii add).
        return min(curvature_radius(y, x) * svd(y)[1] ** 2 / svd(y)[0] for ops in convex_parts(leaf) for y in ops)
    if leaf.kind == "linear_extrude":
        return extrusion_curvature(leaf)
    if leaf.kind == "rotate_extrude":
        q = object_point(leaf, x)
        return max(min(math.hypot(q[0], q[1]), extrusion_curvature(leaf)), 1e-300)
    if leaf.kind == "sphere":
        return p["r"]
    if leaf.kind == "torus":
        return min(p["r"], p["R"] - p["r"])
    if leaf.kind == "cylinder":
        q = object_point(leaf, x)
        return max(math.hypot(q[0], q[1]), 1e-300)
    return math.inf


def face_class(leaf, x):
    """Which smooth piece of the leaf's surface world point x is on."""
    p = leaf.params
    if leaf.kind == "cube":
        q = object_point(leaf, x)
        s = p["size"]
        c = np.zeros(3) if p["center"] else s / 2
        u = (q - c) / (s / 2)
        i = int(np.argmax(np.abs(u)))
        return 2 * i + (u[i] > 0)
    if leaf.kind == "cylinder":
        q = object_point(leaf, x)
        z0 = -p["h"] / 2 if p["center"] else 0.0
        z1 = z0 + p["h"]
        f = (q[2] - z0) / p["h"]
        rz = p["r1"] + (p["r2"] - p["r1"]) * f
        d = [abs(q[2] - z0), abs(q[2] - z1), abs(math.hypot(q[0], q[1]) - rz)]
        return int(np.argmin(d))
    if leaf.kind in reader.EXTRUSIONS:
        return extrusion_face(leaf, object_point(leaf, x))
    if leaf.kind == "polyhedron":
        # The face whose plane (through its first point) is nearest;
        # planes computed once a leaf.
        if not hasattr(leaf, "_planes"):
            pts = leaf.params["points"]
            f3 = np.array([f[:3] for f in leaf.params["faces"]])
            a, b, c = pts[f3[:, 0]], pts[f3[:, 1]], pts[f3[:, 2]]
            nrm = np.cross(b - a, c - a)
            ln = np.linalg.norm(nrm, axis=1)
            ok = ln > 0
            nrm[ok] /= ln[ok, None]
            leaf._planes = (nrm, np.einsum("ij,ij->i", nrm, a), ok)
        nrm, off, ok = leaf._planes
        d = np.where(ok, np.abs(nrm @ object_point(leaf, x) - off), np.inf)
        return int(np.argmin(d))
    return 0


SHADOW_EDGES = {}
SHADOW_EXTENT = {}


def features(f):
    """The smooth pieces of a 2-D tree's boundary: ("seg", a, b) per
    polygon edge, ("ellipse", A, c) per circle; a shadow's, the edges of
    the union of its faces (computed once)."""
    if f[0] == "faces":
        if id(f) not in SHADOW_EDGES:
            polys = [np.asarray(l) for l in cross_section(f, 0).to_polygons()]
            SHADOW_EDGES[id(f)] = (f, [("seg", l[i], l[(i + 1) % len(l)]) for l in polys for i in range(len(l))])
        return SHADOW_EDGES[id(f)][1]
    if f[0] == "poly":
        return [("seg", l[i], l[(i + 1) % len(l)]) for l in f[1] for i in range(len(l))]
    if f[0] == "curves":
        return [("seg", a, b_) if c is None else ("quad", reader.bezier_points(a, c, b_)) for a, c, b_ in reader.curve_pieces(f)]
    if f[0] == "ellipse":
        return [f]
    if f[0] == "op" and len(f) == 4 and f[3][0] == "bands":
        # A curved outline offset: its edges' faces lie |d| from them.
        return [("band", x, f[3][1]) for x in features(f[2][0])] + [x for k in f[2][1:] for x in features(k)]
    return [x for k in f[2] for x in features(k)]


QUAD_SAMPLES = np.linspace(0.0, 1.0, 257)[:, None]


def feature_distance(ft, q):
    if ft[0] == "quad":
        # Which piece a point is on: the nearest of dense samples, refined
        # between its neighbours (a classification, not a bound).
        P = ft[1]
        d = np.linalg.norm(reader.bezier_eval(P, QUAD_SAMPLES[:, 0]) - q, axis=1)
        i = int(np.argmin(d))
        lo, hi = QUAD_SAMPLES[max(i - 1, 0), 0], QUAD_SAMPLES[min(i + 1, 256), 0]
        return float(np.linalg.norm(reader.bezier_eval(P, np.linspace(lo, hi, 65)) - q, axis=1).min())
    if ft[0] == "seg":
        a, b = ft[1], ft[2]
        e = b - a
        ee = float(e @ e)
        u = min(1.0, max(0.0, float((q - a) @ e) / ee)) if ee > 0 else 0.0
        return float(np.linalg.norm(q - a - u * e))
    A, c = ft[1], ft[2]
    r = float(np.linalg.norm(np.linalg.solve(A, q - c)))
    return abs(r - 1) * float(np.linalg.svd(A, compute_uv=False)[-1])


def extrusion_face(leaf, q):
    """Caps 0 and 1 (or the cuts of a partial turn), 2 + k the boundary
    piece k of the 2-D tree that the side over it comes from."""
    p = leaf.params
    if leaf.kind == "linear_extrude":
        h, z0 = p["h"], p["z0"]
        if not hasattr(leaf, "_features"):
            leaf._features = seg_arrays(features(p["flat"]))
        fts = leaf._features
        if reader.twisted(p):
            tq = (q[2] - z0) / h
            sx, sy = p["scale2"]
            ok = 1 + (sx - 1) * tq > 0 and 1 + (sy - 1) * tq > 0
            q2 = reader.twist_frame(p, tq) @ q[:2] if ok else q[:2] * 0
        else:
            w = 1 + (p["scale"] - 1) * (q[2] - z0) / h
            q2 = q[:2] / w if w > 0 else q[:2] * 0
        cand = [abs(q[2] - z0), abs(q[2] - z0 - h)] + feature_distances(fts, q2)
        return int(np.argmin(cand))
    f, flip = reader.revolve_setup(p)
    # Points off the axis are nearest the same piece of a polygon whether
    # or not it was cut to x >= 0 first.
    if not hasattr(leaf, "_features"):
        leaf._features = seg_arrays(features(f))
    fts = leaf._features
    q2 = np.array([math.hypot(q[0], q[1]), q[2]])
    cuts = [math.inf, math.inf]
    if p["angle"] != 360:
        cuts = [abs(float(n @ q)) for n in reader.wedge_normals(p["angle"], flip)]
    cand = cuts + feature_distances(fts, q2)
    return int(np.argmin(cand))


def seg_arrays(fts):
    """Features, with their segments' ends as arrays when all are straight
    (so that feature_distances takes them at once); else with the curved
    pieces grouped by degree — their indices, control points and
    QUAD_SAMPLES points — so that feature_distances takes each group at
    once (the same arithmetic as feature_distance, element by element).
    A band (an offset curved outline's edge) is its edge, with the
    distance |d| subtracted after."""
    sub = np.array([ft[2] if ft[0] == "band" else 0.0 for ft in fts])
    fts = [ft[1] if ft[0] == "band" else ft for ft in fts]
    if fts and all(ft[0] == "seg" for ft in fts):
        return (fts, np.array([ft[1] for ft in fts], float), np.array([ft[2] for ft in fts], float), sub)
    groups = {}
    for i, ft in enumerate(fts):
        if ft[0] == "quad":
            groups.setdefault(len(ft[1]), []).append(i)
    quads = []
    for idx in groups.values():
        P = np.array([fts[i][1] for i in idx], float)
        S = np.array([reader.bezier_eval(fts[i][1], QUAD_SAMPLES[:, 0]) for i in idx])
        quads.append((idx, P, S))
    return (fts, None, quads, sub)


def bezier_eval_rows(P, u):
    """reader.bezier_eval of each row: control points P (m, k + 1, 2) at
    parameters u (m, s)."""
    u = u[..., None]
    k = P.shape[1] - 1
    return sum(math.comb(k, i) * (1 - u) ** (k - i) * u**i * P[:, None, i, :] for i in range(k + 1))


def feature_distances(fts, q):
    """feature_distance for each feature of seg_arrays' answer."""
    fts, a, b, sub = fts
    if sub.any():
        return list(np.abs(np.array(feature_distances((fts, a, b, sub * 0), q)) - sub))
    if a is None:
        out = [None if ft[0] == "quad" else feature_distance(ft, q) for ft in fts]
        for idx, P, S in b:
            j = np.argmin(np.linalg.norm(S - q, axis=2), axis=1)
            lo, hi = QUAD_SAMPLES[np.maximum(j - 1, 0), 0], QUAD_SAMPLES[np.minimum(j + 1, 256), 0]
            u = np.linspace(lo, hi, 65, axis=1)
            d = np.linalg.norm(bezier_eval_rows(P, u) - q, axis=2).min(axis=1)
            for k, i in enumerate(idx):
                out[i] = float(d[k])
        return out
    e = b - a
    ee = np.einsum("ij,ij->i", e, e)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(ee > 0, np.einsum("ij,ij->i", q - a, e) / ee, 0.0)
    u = np.clip(u, 0.0, 1.0)
    return list(np.linalg.norm(q - a - u[:, None] * e, axis=1))


def ieee_div(a, b):
    """a / b as IEEE (and numpy) divide: ±inf for a nonzero a over a zero b
    (signed zeros kept), NaN for 0/0."""
    if b != 0.0:
        return a / b
    if a == 0.0 or a != a:
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def slab_range(lo, hi, o, v):
    """(near, far) of the line o + t·v through the box [lo, hi], by the
    slab rule numpy's vector form used before: per axis the smaller and
    larger of the two slab distances; a NaN nearer distance counts as −∞
    and a NaN farther one as +∞, and an axis whose other distance is NaN
    is passed over."""
    near, far = [], []
    for li, hi_, oi, vi in zip(lo, hi, o, v):
        t0, t1 = ieee_div(li - oi, vi), ieee_div(hi_ - oi, vi)
        nan0, nan1 = t0 != t0, t1 != t1
        near.append(-math.inf if nan0 else math.nan if nan1 else min(t0, t1))
        far.append(math.inf if nan1 else math.nan if nan0 else max(t0, t1))
    near = [x for x in near if x == x]
    far = [x for x in far if x == x]
    return (max(near) if near else math.nan), (min(far) if far else math.nan)


class Caster:
    """All crossings of a ray with the mesh, fast.

    manifold's ray_cast looks up candidate triangles by the box of the ray
    segment, so a long diagonal segment tests nearly every triangle. The
    ray is therefore clipped to the box of the bounded solids and cast in
    PIECES short segments; beyond that box only top-level halfspaces can be
    hit, and they are cast against separately (12 triangles each).
    """

    PIECES = 8

    def __init__(self, sc, n):
        lo, hi = reader.bounded_box(sc, reader.UNIT)
        size = float(np.linalg.norm(hi - lo))
        self.big = 1e6 * max(size, 1.0)
        margin = 1e-6 * max(size, 1.0)
        # (plain floats: the box is clipped against one ray at a time)
        self.lo, self.hi = (lo - margin).tolist(), (hi + margin).tolist()
        self.parts = []  # (leaf, its own mesh, its box)
        root = sc.root
        tops = root.children if isinstance(root, reader.Op) and root.op == "union" else [root]
        halves = [c for c in tops if isinstance(c, reader.Leaf) and c.kind == "halfspace"]
        for x in sc.leaves:
            if x.kind == "halfspace" and x not in halves:
                raise ValueError("a halfspace below the top-level union is not supported by the oracle")
        # The whole solid inside the box; the halfspaces alone beyond it.
        self.solid = self.mesh(root, n) if root else mf.Manifold()
        self.outside = self.combine(halves, n, mf.OpType.Add) if halves else None

    def mesh(self, node, n):
        if isinstance(node, reader.Leaf):
            m = leaf_mesh(node, n, self.big)
            b = m.bounding_box()
            self.parts.append((node, m, [float(c) for c in b[:3]], [float(c) for c in b[3:]]))
            return m
        op = {"union": mf.OpType.Add, "intersection": mf.OpType.Intersect}.get(node.op)
        if op is not None:
            return self.combine(node.children, n, op)
        return self.mesh(node.children[0], n) - self.mesh(node.children[1], n)

    def combine(self, nodes, n, op):
        kids = [self.mesh(c, n) for c in nodes]
        return kids[0] if len(kids) == 1 else mf.Manifold.batch_boolean(kids, op) if kids else mf.Manifold()

    def owner(self, x, v, nrm):
        """The leaf whose own mesh holds the hit at x: a boolean keeps the
        triangles of its operands (clipped in their planes), so exactly
        the leaf whose mesh the ray crosses at x, with the same normal up
        to sign, made that surface. (manifold's face_id numbers its inner
        order, not the leaves.)"""
        eps = 1e-7 * max(1.0, float(np.abs(x).max()))
        xs = x.tolist()
        for leaf, m, lo, hi in self.parts:
            # The box test in plain floats: numpy's per-call cost on three
            # numbers was a tenth of the oracle's time.
            if any(xi < li - eps or xi > hj + eps for xi, li, hj in zip(xs, lo, hi)):
                continue
            for h in m.ray_cast((x - eps * v).tolist(), (x + eps * v).tolist()):
                if abs(float(np.dot(h.normal, nrm))) > 1 - 1e-6:
                    return leaf
        return None

    @staticmethod
    def _seg(m, o, v, a, b):
        return [
            (a + h.distance * (b - a), np.array(h.normal, dtype=float))
            for h in m.ray_cast((o + a * v).tolist(), (o + b * v).tolist())
        ]

    def cast_all(self, o, v, tmax=math.inf, first=False, owners=True):
        """[(t, normal, leaf)] of the crossings with 0 < t < tmax along
        unit v, sorted (only the first one if `first`; leaf None unless
        `owners`)."""
        hits = self._cast(o, v, tmax, first)
        return [(t, n, self.owner(o + t * v, v, n) if owners else None) for t, n in hits]

    def _cast(self, o, v, tmax, first):
        near, far = slab_range(self.lo, self.hi, o.tolist(), v.tolist())
        near = max(near, 0.0)
        inside = near <= far and math.isfinite(far) and near < tmax
        hits = []
        if self.outside is not None and inside and near > 0:
            hits += self._seg(self.outside, o, v, 0.0, min(near, tmax))
            if first and hits:
                return hits[:1]
        if inside:
            # np.linspace's points: start + i·step, the last one the end.
            end = min(far, tmax)
            step = (end - near) / self.PIECES
            edges = [i * step + near for i in range(self.PIECES)] + [end]
            for a, b in zip(edges, edges[1:]):
                hits += [h for h in self._seg(self.solid, o, v, a, b) if h[0] > 0]
                if first and hits:
                    return sorted(hits, key=lambda h: h[0])[:1]
        if self.outside is not None:
            start = far if inside else 0.0
            end = min(4 * self.big, tmax)
            if start < end:
                # The stand-in box's far faces are not surfaces of the halfspace.
                hits += [h for h in self._seg(self.outside, o, v, start, end) if np.abs(o + h[0] * v).max() <= self.big / 4]
        hits = sorted((h for h in hits if 0 < h[0] < tmax), key=lambda h: h[0])
        return hits[:1] if first else hits

    def cast(self, o, v):
        h = self.cast_all(o, v, first=True)
        return h[0] if h else None

    def blocked(self, o, v, tmax):
        h = self._cast(o, v, tmax, True)
        return h[0] if h else None


# --------------------------------------------------------------------------
# csgrt's side
# --------------------------------------------------------------------------


def camera_rays(view, w, h):
    eye, lookat, up, fov = (np.asarray(x, dtype=float) if i < 3 else x for i, x in enumerate(view))
    look = lookat - eye
    du = np.cross(look, up)
    du /= np.linalg.norm(du)
    dv = np.cross(look, du)
    dv /= np.linalg.norm(dv)
    fl = w / (2 * math.tan(math.radians(fov) / 2))
    vp = look / np.linalg.norm(look) * fl - 0.5 * (w * du + h * dv)
    out = []
    for j in range(h):
        for i in range(w):
            d = (i + 0.5) * du + (j + 0.5) * dv + vp
            out.append((eye, d / np.linalg.norm(d)))
    return out


def random_rays(sc, count, seed):
    """Rays from a sphere around the bounded solids towards random points
    of their box."""
    rng = np.random.default_rng(seed)
    lo, hi = reader.bounded_box(sc, reader.UNIT)
    c, r = (lo + hi) / 2, max(np.linalg.norm(hi - lo) / 2, 1e-9)
    out = []
    for _ in range(count):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        target = c + rng.uniform(-0.5, 0.5, size=3) * (hi - lo)
        o = c + 2 * r * u
        d = target - o
        out.append((o, d / np.linalg.norm(d)))
    return out


def run_csgrt(cmd, scene, work, w, h, rays, env=None):
    """csgrt's image, mask and traced rays."""
    mask, image = os.path.join(work, "mask.png"), os.path.join(work, "image.png")
    subprocess.run(
        [*cmd, scene, "--size", f"{w}x{h}", "--spp", "1", "--mask", mask, "-o", image, "-q"], check=True, env=env
    )
    m = np.asarray(Image.open(mask).convert("L")) == 255
    img = np.asarray(Image.open(image).convert("RGB")).astype(int)
    ray_file = os.path.join(work, "rays.txt")
    with open(ray_file, "w") as f:
        for o, v in rays:
            f.write(" ".join(repr(float(x)) for x in (*o, *v)) + "\n")
    out = subprocess.run(
        [*cmd, scene, "--trace-rays", ray_file], check=True, capture_output=True, text=True, env=env
    ).stdout.splitlines()
    if len(out) != len(rays):
        raise RuntimeError(f"csgrt answered {len(out)} of {len(rays)} rays")
    traced = []
    for line in out:
        if line == "miss":
            traced.append(None)
        else:
            t, nx, ny, nz = map(float, line.split())
            traced.append((t, np.array([nx, ny, nz])))
    return m, img, traced


# --------------------------------------------------------------------------
# Comparison
# --------------------------------------------------------------------------


def mixed(grid):
    """Pixels whose 3x3 neighbourhood holds more than one value of grid."""
    h, w = grid.shape
    p = np.pad(grid, 1, mode="edge")
    out = np.zeros((h, w), dtype=bool)
    for dy in range(3):
        for dx in range(3):
            out |= p[dy : dy + h, dx : dx + w] != grid
    return out


def judge(o, v, c, m, n):
    """(ok, depth error, depth bound, angle, angle bound) of one ray:
    csgrt's answer c against the mesh's m."""
    if (c is None) != (m is None):
        return False, None, None, None, None
    if c is None:
        return True, 0.0, math.inf, 0.0, math.inf
    (tc, nc), (tm, nm, leaf) = c, m
    delta = facet_distance(leaf, n) if leaf else 0.0
    cos = abs(float(v @ nc))
    big = largest_radius(leaf) if leaf else 0.0
    scale = float(np.abs(o).max() + tc)
    dbound = min(2 * delta / cos if cos > 0 else math.inf, 2 * math.sqrt(2 * big * delta)) + 1e-9 * scale
    err = abs(tc - tm)
    angle = math.acos(max(-1.0, min(1.0, float(nc @ nm))))
    abound = FP_ANGLE
    if leaf:
        smax, smin = svd(leaf)
        kappa = smax / smin
        rho = curvature_radius(leaf, o + tm * v)
        abound += facet_angle(leaf, n) + kappa * (err + delta) / (smin * rho)
    return err <= dbound and angle <= abound, err, dbound, angle, abound


class Side:
    """What the oracle sees of one scene at n segments, csgrt aside: the
    mesh's first hit through every pixel centre and along every random
    ray, the hit and surface maps, and the edge pixels."""

    def __init__(self, sc, n, w, h, pix_rays, rays):
        self.n = n
        self.caster = Caster(sc, n)
        self.hit = np.zeros((h, w), dtype=bool)
        surf = np.full((h, w), -1, dtype=np.int64)
        self.pixels = []
        for k, (o, v) in enumerate(pix_rays):
            j, i = divmod(k, w)
            m = self.caster.cast(o, v)
            self.pixels.append(m)
            if m is not None:
                self.hit[j, i] = True
                surf[j, i] = (m[2].id * 1_000_000 + face_class(m[2], o + m[0] * v)) if m[2] else -2
        self.edge = mixed(surf)
        self.rays = [self.caster.cast(o, v) for o, v in rays]


def compare(name, sc, side, w, h, cmask, img, pix_rays, pix_traced, rays, traced, out_dir, colour):
    n, hit, edge = side.n, side.hit, side.edge
    bad = np.zeros((h, w), dtype=bool)
    worst_depth, worst_angle, worst_ratio = 0.0, 0.0, 0.0
    for k, ((o, v), c) in enumerate(zip(pix_rays, pix_traced)):
        j, i = divmod(k, w)
        ok, err, db, ang, ab = judge(o, v, c, side.pixels[k], n)
        bad[j, i] = not ok
        if not edge[j, i] and err is not None and c is not None:
            worst_depth, worst_angle = max(worst_depth, err), max(worst_angle, ang)
    mask_bad = cmask != hit
    off_edge = int(np.sum((bad | mask_bad) & ~edge))
    # Random rays.
    ray_bad, ray_worst = 0, None
    for (o, v), c, m in zip(rays, traced, side.rays):
        ok, err, db, ang, ab = judge(o, v, c, m, n)
        if not ok:
            ray_bad += 1
            r = max(err / db, ang / ab) if err is not None else math.inf
            if ray_worst is None or r > ray_worst[0]:
                ray_worst = (r, o, v, c, err, db, ang, ab)
        elif c is not None:
            worst_depth, worst_angle = max(worst_depth, err), max(worst_angle, ang)
            worst_ratio = max(worst_ratio, err / db, ang / ab)
    row = {
        "n": n,
        "mismatch": int(np.sum(bad | mask_bad)),
        "off_edge": off_edge,
        "mask_off_edge": int(np.sum(mask_bad & ~edge)),
        "edge": int(np.sum(edge)),
        "rays": len(rays),
        "ray_bad": ray_bad,
        "ray_worst": ray_worst,
        "worst_ratio": worst_ratio,
        "worst_depth": worst_depth,
        "worst_angle": math.degrees(worst_angle),
        "colour_checked": 0,
        "colour_bad": 0,
        "colour_first": None,
    }
    if colour:
        colour_check(sc, side.caster, w, h, img, pix_rays, pix_traced, side.pixels, edge, n, row)
    if out_dir and (off_edge or row["colour_bad"]):
        diff = np.zeros((h, w, 3), dtype=np.uint8) + 255
        diff[hit & ~bad] = (200, 200, 200)
        diff[bad | mask_bad] = (30, 60, 220)
        diff[(bad | mask_bad) & ~edge] = (220, 30, 30)
        Image.fromarray(diff).save(os.path.join(out_dir, f"{name}-n{n}-diff.png"))
    return row


def towards(kind, x, p):
    """The unit direction from p to a light and its distance."""
    if kind == "directional":
        return -x, math.inf
    d = float(np.linalg.norm(x - p))
    return (x - p) / d, d


def off_surface(p, nrm, ldir, delta, scale):
    """Where a shadow ray from surface point p starts: beyond the
    faceting (the exact surface may lie inside the mesh by delta), on the
    side the light is."""
    return p + (nrm if nrm @ ldir > 0 else -nrm) * (4 * delta + 1e-7 * scale)


def colour_check(sc, caster, w, h, img, pix_rays, pix_traced, mesh, edge, n, row):
    """Shade every opaque, non-reflective pixel off the edges; first pass
    the shadow maps (to find ambiguous shadows), then the colours."""
    transparent = any(x.material["kt"] > 0 for x in sc.leaves)
    lights = [k for k, (kind, _, _) in enumerate(sc.lights) if kind != "ambient"]
    todo = []
    for k, ((o, v), c) in enumerate(zip(pix_rays, pix_traced)):
        j, i = divmod(k, w)
        m = mesh[k]
        if edge[j, i] or c is None or m is None or m[2] is None:
            continue
        if m[2].material["kr"] > 0 or m[2].material["kt"] > 0:
            continue
        todo.append(k)
    # Shadow maps per light, to find the ambiguous pixels.
    shadow = np.full((len(lights), h, w), -1, dtype=np.int64)
    info = {}
    for k in todo:
        j, i = divmod(k, w)
        (o, v), (tc, nc), leaf = pix_rays[k], pix_traced[k], mesh[k][2]
        p = o + tc * v
        delta = facet_distance(leaf, n)
        scale = float(np.abs(o).max() + tc)
        info[k] = (p, nc, leaf, delta, scale)
        for li, L in enumerate(lights):
            kind, _, x = sc.lights[L]
            ldir, dist = towards(kind, x, p)
            shadow[li, j, i] = 1 if caster.blocked(off_surface(p, nc, ldir, delta, scale), ldir, dist) else 0
    shadow_edge = np.zeros((len(lights), h, w), dtype=bool)
    for li in range(len(lights)):
        shadow_edge[li] = mixed(shadow[li])
    for k in todo:
        j, i = divmod(k, w)
        p, nc, leaf, delta, scale = info[k]
        v = pix_rays[k][1]
        mat = leaf.material
        ns = -nc if nc @ v > 0 else nc
        col = np.zeros(3)
        options = [np.zeros(3)]
        for li_all, (kind, il, x) in enumerate(sc.lights):
            if kind == "ambient":
                col += mat["ka"] * il * mat["color"]
                continue
            li = lights.index(li_all)
            ldir, dist = towards(kind, x, p)
            ndl = float(ns @ ldir)
            if ndl <= 0 or (mat["kd"] <= 0 and mat["ks"] <= 0):
                continue
            term = mat["kd"] * ndl * mat["color"] * il
            if mat["ks"] > 0:
                r = 2 * ndl * ns - ldir
                vr = float(-v @ r)
                if vr > 0:
                    term = term + mat["ks"] * vr ** mat["ns"] * il
            if transparent:
                pass_ = 1.0
                for t, hn, hl in caster.cast_all(off_surface(p, nc, ldir, delta, scale), ldir, dist):
                    if hn @ ldir < 0:
                        pass_ *= hl.material["kt"] if hl else 0.0
            else:
                pass_ = 0.0 if shadow[li, j, i] else 1.0
            choices = {pass_}
            if shadow_edge[li, j, i] or ndl < 0.02:
                choices |= {0.0, 1.0}
            options = [o + q * term for o in options for q in sorted(choices)]
        want = [np.round(np.clip(col + o, 0, 1) * 255) for o in options]
        got = img[j, i]
        row["colour_checked"] += 1
        if min(np.abs(got - x).max() for x in want) > COLOUR_TOLERANCE:
            row["colour_bad"] += 1
            if row["colour_first"] is None:
                row["colour_first"] = (i, j, got.tolist(), [x.astype(int).tolist() for x in want])


def verdict(rows):
    """Problems with one scene's rows (coarsest n first), in words."""
    bad = []
    for r in rows:
        if r["off_edge"]:
            bad.append(
                f"n={r['n']}: {r['off_edge']} pixels disagree off the edges "
                f"({r['mask_off_edge']} of them in csgrt's own mask)"
            )
    r = rows[-1]
    if r["ray_bad"]:
        q, o, v, c, err, db, ang, ab = r["ray_worst"]
        ray = " ".join(f"{x:.17g}" for x in (*o, *v))
        if err is None:
            bad.append(f"n={r['n']}: {r['ray_bad']} rays disagree; hit/miss on the ray {ray} (csgrt: {c})")
        else:
            bad.append(
                f"n={r['n']}: {r['ray_bad']} rays beyond their bounds; worst: the ray {ray}: "
                f"depth error {err:.3g} (bound {db:.3g}), normal {math.degrees(ang):.3g} deg (bound {math.degrees(ab):.3g})"
            )
    if r["colour_bad"]:
        i, j, got, want = r["colour_first"]
        bad.append(
            f"{r['colour_bad']} of {r['colour_checked']} shaded pixels have the wrong colour; "
            f"first: pixel ({i}, {j}) is {got}, the file says {want}"
        )
    for key in ("mismatch", "ray_bad"):
        seq = [r[key] for r in rows]
        for a, b, r in zip(seq, seq[1:], rows[1:]):
            if b > a + GROW_SLACK:
                bad.append(f"{key} grew from {a} to {b} at n={r['n']}")
        if seq[0] > 0 and seq[-1] >= seq[0] and seq[-1] > GROW_SLACK:
            bad.append(f"{key} did not shrink: {seq}")
    return bad


SIDES = {}  # (path, w, h, rays, n) -> Side: the oracle's side, once a process


def check_scene(path, cmd, w, h, segs, nrays, out_dir=None, env=None, first_fault=False):
    """(rows, problems) for one scene; cmd is csgrt's command line, env
    its environment (None: this one). With first_fault (a build that must
    fail: tools/oracle/mutants.py), stop at the first n whose pixels disagree off
    the edges — a problem whatever the finer n show."""
    name = os.path.splitext(os.path.basename(path))[0]
    try:
        sc = reader.read(path)
    except reader.ReadError as e:
        return [], [f"the oracle cannot read it: {e}"]
    view = sc.view(w, h)
    pix_rays = camera_rays(view, w, h)
    rays = random_rays(sc, nrays, seed_of(name))
    with tempfile.TemporaryDirectory() as work:
        try:
            cmask, img, traced = run_csgrt(cmd, path, work, w, h, pix_rays + rays, env)
        except (subprocess.CalledProcessError, RuntimeError, ValueError) as e:
            return [], [f"csgrt failed: {e}"]
    pix_traced, traced = traced[: len(pix_rays)], traced[len(pix_rays) :]
    rows = []
    for n in segs:
        key = (os.path.abspath(path), w, h, nrays, n)
        if key not in SIDES:
            SIDES[key] = Side(sc, n, w, h, pix_rays, rays)
        side = SIDES[key]
        rows.append(
            compare(name, sc, side, w, h, cmask, img, pix_rays, pix_traced, rays, traced, out_dir, n == segs[-1])
        )
        if first_fault and rows[-1]["off_edge"]:
            break
    return rows, verdict(rows)


def same_outputs(path, cmd, other, w, h, nrays, env=None):
    """Problems (none: the same) where csgrt's command `cmd` (under env)
    answers differently from `other` on everything check_scene reads of
    it — the mask, the image, the pixel-centre and random rays — so that
    the oracle's verdict on one is its verdict on the other, without
    meshing the scene again."""
    name = os.path.splitext(os.path.basename(path))[0]
    sc = reader.read(path)
    view = sc.view(w, h)
    rays = camera_rays(view, w, h) + random_rays(sc, nrays, seed_of(name))
    outs = []
    for c, e in ((cmd, env), (other, None)):
        with tempfile.TemporaryDirectory() as work:
            cmask, img, traced = run_csgrt(c, path, work, w, h, rays, e)
        outs.append((np.asarray(cmask), np.asarray(img), traced))
    (m0, i0, t0), (m1, i1, t1) = outs
    bad = []
    if not np.array_equal(m0, m1):
        bad.append("the masks differ")
    if not np.array_equal(i0, i1):
        bad.append("the images differ")
    if repr(t0) != repr(t1):
        bad.append("the traced rays differ")
    return bad


TABLE_HEAD = [
    "| scene | n | pixels disagreeing (off edge) | edge pixels | rays beyond bound | worst depth err | worst normal angle | worst ray err/bound | colours checked (wrong) |",
    "|---|---|---|---|---|---|---|---|---|",
]


def table_row(name, r):
    col = f"{r['colour_checked']} ({r['colour_bad']})" if r["colour_checked"] else ""
    return (
        f"| {name} | {r['n']} | {r['mismatch']} ({r['off_edge']}) | {r['edge']} | {r['ray_bad']}/{r['rays']} | "
        f"{r['worst_depth']:.3g} | {r['worst_angle']:.3g}° | {r['worst_ratio']:.3g} | {col} |"
    )


def one(job):
    scene, cmd, w, h, segs, rays, out = job
    start = time.monotonic()
    got = check_scene(scene, cmd, w, h, segs, rays, out)
    return got, time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--csgrt", default="target/release/csgrt", help="the binary, or a command line")
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--segments", default="64,128,256,512")
    ap.add_argument("--rays", type=int, default=400)
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="scenes checked at once")
    ap.add_argument("--out", default=None, help="folder for diff pictures")
    ap.add_argument("--check", action="store_true", help="exit 1 if a scene fails")
    ap.add_argument("--table", default=None, help="write the table (Markdown) here")
    a = ap.parse_args()
    segs = [int(s) for s in a.segments.split(",")]
    w, h = map(int, a.size.split("x"))
    if a.out:
        os.makedirs(a.out, exist_ok=True)
    lines = list(TABLE_HEAD)
    failed = []
    jobs = [(s, a.csgrt.split(), w, h, segs, a.rays, a.out) for s in a.scenes]
    # A fresh worker for each scene: what one scene's meshes leave in a
    # worker's heap is not carried into the next (a long-lived worker grew
    # past 14 GB on CI).
    with multiprocessing.Pool(max(1, a.jobs), maxtasksperchild=1) as pool:
        for scene, ((rows, bad), took) in zip(a.scenes, pool.imap(one, jobs)):
            name = os.path.splitext(os.path.basename(scene))[0]
            print(f"{name}: {took:.1f} s", file=sys.stderr, flush=True)
            for r in rows:
                lines.append(table_row(name, r))
                print(lines[-1], flush=True)
            if bad:
                failed.append(name)
                for b in bad:
                    print(f"FAIL {name}: {b}", file=sys.stderr, flush=True)
    if a.table:
        head = [
            "# Oracle: csgrt against manifold3d meshes of the file's own reading",
            "",
            f"Generated by `.venv/bin/python -m tools.oracle.oracle --table docs/oracle.md {' '.join(a.scenes)}`",
            f"({w}×{h}, {a.rays} random rays a scene besides one through every pixel centre). The oracle",
            "reads each file itself (tools/oracle/scene/). Per scene and number of segments n: pixels where",
            "csgrt and the mesh disagree (hit/miss, depth beyond its bound, normal beyond its bound, or",
            "csgrt's own mask), and how many of them are off the oracle's edges (must be 0); the edge",
            "pixels; random rays beyond their bounds (must be 0 at the finest n); the worst depth error",
            "(scene units) and normal angle over every pixel off the edges and every ray; the worst ray's",
            "error over its bound; and at the finest n the shaded pixels whose colour was checked, with",
            "the number wrong (must be 0). The bounds are derived at the top of tools/oracle/oracle.py.",
            "",
        ]
        with open(a.table, "w") as f:
            f.write("\n".join(head + lines) + "\n")
    print(f"{len(a.scenes) - len(failed)} passed, {len(failed)} failed")
    if a.check and failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
