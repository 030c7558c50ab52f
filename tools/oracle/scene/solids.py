"""Measures of 3-D leaves: resize's exact extents, slices and shadows of
leaves (projection), twists and turns of extrusions."""

import math

import numpy as np

from . import bounds
from . import meaning
from . import plane

__all__ = ['ccw', 'check_twistable', 'clip_poly', 'conic_ellipse', 'exact_box', 'flat_box', 'flat_extent_exact', 'half_planes', 'has_slice', 'largest_stretch', 'mesh_slice', 'moved_node', 'resize_args', 'revolve_setup', 'section_tree', 'shadow_tree', 'slab_rows', 'twist_frame', 'twisted', 'wedge_normals']


def resize_args(rd, s, a):
    ns = a.get("newsize", [])
    ns = [float(x) for x in ns] if isinstance(ns, list) else []
    ns = (ns + [0.0, 0.0, 0.0])[:3]
    au = a.get("auto", False)
    au = [bool(x) for x in au] if isinstance(au, list) else [bool(au)] * 3
    return ns, (au + [False, False, False])[:3]


def flat_extent_exact(rd, s, f, i):
    """The exact extent of a 2-D tree along axis i: leaves exactly, a union
    the join, a difference its first operand's when no subtracted box
    reaches its sides; anything else is not in the oracle."""
    if f[0] == "poly":
        v = np.concatenate([l[:, i] for l in f[1]])
        return v.min(), v.max()
    if f[0] == "curves":
        lo, hi = plane.curve_extent(f)
        return lo[i], hi[i]
    if f[0] == "ellipse":
        h = float(np.linalg.norm(f[1][i]))
        return f[2][i] - h, f[2][i] + h
    if f[0] == "section":
        raise rd.err(s, "a resized projection is not in the oracle")
    rs = [flat_extent_exact(rd, s, k, i) for k in f[2]]
    if f[1] in ("union", "hull"):
        return min(r[0] for r in rs), max(r[1] for r in rs)
    if f[1] == "difference" and all(r[0] > rs[0][0] and r[1] < rs[0][1] for r in rs[1:]):
        return rs[0]
    if f[1] == "xor":
        # Even-odd: a far side only one operand reaches is in the result.
        lo, hi = min(r[0] for r in rs), max(r[1] for r in rs)
        if sum(r[0] == lo for r in rs) == 1 and sum(r[1] == hi for r in rs) == 1:
            return lo, hi
    raise rd.err(s, f"the extent of this 2-D {f[1]} is not in the oracle")


def exact_box(rd, s, node):
    """The exact box of a 3-D tree: each primitive's closed form (an
    extrusion's only under an axis-aligned matrix, where csgrt's framing
    box is exact), a union's join, a difference's first operand's when no
    subtracted box reaches its sides; anything else is not in the oracle."""
    if isinstance(node, meaning.Leaf):
        if node.kind in meaning.EXTRUSIONS:
            L = node.matrix[:3, :3]
            if node.kind != "linear_extrude" or twisted(node.params) or np.count_nonzero(L - np.diag(np.diag(L))):
                raise rd.err(s, "the exact extent of this extrusion is not in the oracle")
        if node.kind == "halfspace":
            raise rd.err(s, "the extent of a halfspace is not in the oracle")
        return bounds.leaf_box(node)
    bs = [exact_box(rd, s, c) for c in node.children]
    if node.op == "union":
        return bounds.combine_boxes("union", bs)
    if node.op == "difference" and all(np.all(b[0] > bs[0][0]) and np.all(b[1] < bs[0][1]) for b in bs[1:]):
        return bs[0]
    raise rd.err(s, f"the extent of this {node.op} is not in the oracle")


def has_slice(leaf):
    """Whether an extrusion leaf holds a projection's slice."""
    rec = lambda f: f[0] == "framed" or f[0] == "op" and any(rec(k) for k in f[2])
    return "frame" in leaf.params and rec(leaf.params["frame"])


def moved_node(node, M):
    """A 3-D tree with every leaf placed by M first."""
    if isinstance(node, meaning.Leaf):
        x = meaning.Leaf(node.kind, node.params, M @ node.matrix, node.material, node.stmt)
        return x
    return meaning.Op(node.op, [moved_node(c, M) for c in node.children])


def clip_poly(poly, g, c):
    """The convex polygon poly (k x 2) cut to g . p <= c (Sutherland-Hodgman)."""
    out = []
    k = len(poly)
    for i in range(k):
        a, b = poly[i], poly[(i + 1) % k]
        fa, fb = g @ a - c, g @ b - c
        if fa <= 0:
            out.append(a)
        if (fa < 0 < fb) or (fb < 0 < fa):
            out.append(a + (b - a) * (fa / (fa - fb)))
    return np.array(out) if len(out) >= 3 else None


def half_planes(poly, rows):
    """poly cut by each (g, c): g . p <= c; None when nothing is left. A
    row with g = 0 keeps all or nothing."""
    for g, c in rows:
        if not np.any(g):
            if 0.0 > c:
                return None
            continue
        poly = clip_poly(poly, g, c)
        if poly is None:
            return None
    return poly


def slab_rows(P, w, i, lo, hi):
    """The half-planes lo <= (P p + w)_i <= hi, a row exactly zero when P's
    row is negligible (a face parallel to the plane)."""
    g = P[i].copy()
    if np.linalg.norm(g) <= 1e-13 * np.linalg.norm(P):
        g[:] = 0.0
    return [(g, hi - w[i]), (-g, w[i] - lo)]


def conic_ellipse(Q, w, r):
    """The ellipse {p : |Q p + w| <= r} for Q of full column rank, as
    ("ellipse", A, c) (the image of the unit disc), or None when empty."""
    G = Q.T @ Q
    c = -np.linalg.solve(G, Q.T @ w)
    k = r * r - w @ w + c @ G @ c
    if k <= 0:
        return None
    A = math.sqrt(k) * np.linalg.cholesky(np.linalg.inv(G))
    return ("ellipse", A, c)


def mesh_slice(node):
    """The slice z = 0 of a placed mesh as ("poly", loops), filled even-odd:
    each face edge with ends on both sides meets the plane at one point
    (computed once an edge, so the two faces of an edge share it); a face
    crossing the plane gives the segment between its two such points, and
    the segments chain into loops. A point exactly in the plane is not in
    the oracle (which side it counts for is a convention)."""
    pts = node.params["points"] @ node.matrix[:3, :3].T + node.matrix[:3, 3]
    z = pts[:, 2]
    if np.any(z == 0):
        raise ValueError("a mesh point exactly in the slicing plane is not in the oracle")
    cut = {}

    def at(i, j):
        key = (min(i, j), max(i, j))
        if key not in cut:
            a, b = pts[key[0]], pts[key[1]]
            f = a[2] / (a[2] - b[2])
            cut[key] = len(cut), (a + f * (b - a))[:2]
        return cut[key][0]

    nxt = {}
    for f in node.params["faces"]:
        crossings = [at(f[k], f[(k + 1) % len(f)]) for k in range(len(f)) if (z[f[k]] > 0) != (z[f[(k + 1) % len(f)]] > 0)]
        for k in range(0, len(crossings) - 1, 2):
            a, b = crossings[k], crossings[k + 1]
            nxt.setdefault(a, []).append(b)
            nxt.setdefault(b, []).append(a)
    point = {i: p for i, p in cut.values()}
    loops, seen = [], set()
    for start in nxt:
        if start in seen:
            continue
        loop, prev, cur = [start], None, start
        seen.add(start)
        while True:
            step = [x for x in nxt[cur] if x != prev]
            if not step or step[0] == start:
                break
            prev, cur = cur, step[0]
            if cur in seen:
                break
            seen.add(cur)
            loop.append(cur)
        if len(loop) >= 3:
            loops.append(np.array([point[i] for i in loop]))
    return ("poly", loops) if loops else None


def ccw(loop):
    """A loop turned counter-clockwise."""
    x, y = loop[:, 0], loop[:, 1]
    area = float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return loop if area >= 0 else loop[::-1]


def shadow_tree(node):
    """The shadow on z = 0 of a 3-D union of meshes, boxes and spheres,
    exactly, as a 2-D tree: a mesh's or box's as the union of its faces'
    shadows, ("faces", loops counter-clockwise) filled where any loop is;
    a sphere's, the ellipse E u + c with E E^T = P P^T (P its matrix's x
    and y rows). The shadow of an intersection or a difference is not its
    operands', and not in the oracle; nor a cylinder's."""
    if isinstance(node, meaning.Op):
        if node.op != "union":
            raise ValueError(f"the shadow of a 3-D {node.op} is not in the oracle")
        kids = [k for k in (shadow_tree(c) for c in node.children) if k is not None]
        return None if not kids else kids[0] if len(kids) == 1 else ("op", "union", kids)
    m, p = node.matrix, node.params
    if node.kind == "polyhedron":
        pts = p["points"] @ m[:3, :3].T + m[:3, 3]
        loops = [ccw(pts[f][:, :2]) for f in p["faces"]]
        return ("faces", [l for l in loops if abs(float(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1]))) > 0])
    if node.kind == "cube":
        s0 = -p["size"] / 2 if p["center"] else np.zeros(3)
        c = [np.array([s0[0] + (i & 1) * p["size"][0], s0[1] + (i >> 1 & 1) * p["size"][1], s0[2] + (i >> 2 & 1) * p["size"][2]]) for i in range(8)]
        pts = np.array(c) @ m[:3, :3].T + m[:3, 3]
        faces = [[0, 1, 3, 2], [4, 5, 7, 6], [0, 1, 5, 4], [2, 3, 7, 6], [0, 2, 6, 4], [1, 3, 7, 5]]
        loops = [ccw(pts[f][:, :2]) for f in faces]
        return ("faces", [l for l in loops if abs(float(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1]))) > 0])
    if node.kind == "sphere":
        P = m[:2, :3] * p["r"]
        E = np.linalg.cholesky(P @ P.T)
        return ("ellipse", E, m[:2, 3].copy())
    raise ValueError(f"the shadow of a {node.kind} is not in the oracle")


def flat_box(f):
    """The box (lo, hi) of a shadow tree's leaves (csgrt's framing of it)."""
    if f[0] == "faces":
        pts = np.concatenate(f[1])
        return pts.min(axis=0), pts.max(axis=0)
    if f[0] == "ellipse":
        h = np.sqrt(f[1][:, 0] ** 2 + f[1][:, 1] ** 2)
        return f[2] - h, f[2] + h
    bs = [flat_box(k) for k in f[2]]
    return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)


def section_tree(node, big):
    """The slice z = 0 of a 3-D tree of spheres, boxes, cylinders and
    halfspaces, exactly, as a 2-D tree: a point p of the plane is in a
    leaf when its object point u = P p + w is (P, w from the leaf's inverse
    matrix). A sphere gives the ellipse |u| <= r; a box the polygon of its
    six half-planes; a cylinder the ellipse |u_xy| <= r (or, with its axis
    in the plane, a strip) met with its caps' half-planes; a halfspace a
    half-plane. Polygons are cut from the square `big`."""
    if isinstance(node, meaning.Op):
        kids = [section_tree(c, big) for c in node.children]
        if node.op == "intersection" and any(k is None for k in kids):
            return None
        if node.op == "difference" and kids[0] is None:
            return None
        live = [k for k in kids if k is not None]
        if not live:
            return None
        return live[0] if len(live) == 1 else ("op", node.op, live)
    lo, hi = big
    square = np.array([lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]], dtype=float)
    inv = np.linalg.inv(node.matrix)
    P, w = inv[:3, :2], inv[:3, 3]
    p = node.params
    poly = lambda rows: (lambda q: None if q is None else ("poly", [q]))(half_planes(square, rows))
    if node.kind == "sphere":
        return conic_ellipse(P, w, p["r"])
    if node.kind == "cube":
        s0 = -p["size"] / 2 if p["center"] else np.zeros(3)
        return poly([r for i in range(3) for r in slab_rows(P, w, i, s0[i], s0[i] + p["size"][i])])
    if node.kind == "cylinder" and p["r1"] == p["r2"]:
        z0 = -p["h"] / 2 if p["center"] else 0.0
        caps = slab_rows(P, w, 2, z0, z0 + p["h"])
        Q, r = P[:2], p["r1"]
        U, S, Vt = np.linalg.svd(Q)
        if S[1] <= 1e-13 * S[0]:
            # The axis in the plane: |w + e s| <= r with s = g . p, a strip.
            e, g = U[:, 0], S[0] * Vt[0]
            b, cc = e @ w[:2], w[:2] @ w[:2] - r * r
            disc = b * b - cc
            if disc <= 0:
                return None
            s0, s1 = -b - math.sqrt(disc), -b + math.sqrt(disc)
            return poly(caps + [(g, s1), (-g, -s0)])
        ell = conic_ellipse(Q, w[:2], r)
        if ell is None:
            return None
        if not np.any(caps[0][0]):
            return ell if caps[0][1] >= 0 and caps[1][1] >= 0 else None
        box_ = poly(caps)
        return None if box_ is None else ("op", "intersection", [ell, box_])
    if node.kind == "halfspace":
        n = p["normal"]
        return poly([(n @ P, p["offset"] - n @ w)])
    if node.kind == "polyhedron":
        return mesh_slice(node)
    raise ValueError(f"the slice of a {node.kind} is not in the oracle")


def check_twistable(rd, s, f, twist, sc):
    """The oracle twists and scales polygons, circles, ellipses and DXF
    drawings, not text or SVG drawings."""
    if f[0] == "curves":
        raise rd.err(s, "twisted text is not in the oracle")
    if len(f) == 4 and f[3][0] == "svg":
        raise rd.err(s, "a twisted SVG drawing is not in the oracle")
    if f[0] == "op":
        for k in f[2]:
            check_twistable(rd, s, k, twist, sc)


def twisted(p):
    """Whether an extrusion's parameters twist or scale unevenly."""
    return p.get("scale") is None


def twist_frame(p, t):
    """R(twist t) S(t)^-1 (OpenSCAD's section at fraction t, inverted): a
    world plane point times it is the region's point."""
    sx, sy = p["scale2"]
    sg = np.array([1 + (sx - 1) * t, 1 + (sy - 1) * t])
    a = math.radians(p["twist"]) * t
    c, s_ = math.cos(a), math.sin(a)
    return np.array([[c, -s_], [s_, c]]) @ np.diag(1 / sg)


def revolve_setup(p):
    """(tree at x >= 0, flipped, angle) of a rotate_extrude's parameters;
    raises on a shape across the axis (OpenSCAD's error). Read once, when
    the leaf is made (its "side")."""
    if "side" in p:
        return p["side"]
    f = p["flat"]
    lo, hi = plane.flat_x_range(f)
    # What a combination leaves may lie on one side though its parts reach
    # across (OpenSCAD turns the shape it has computed).
    if lo < 0 < hi and plane.flat_empty_beyond_axis(f, True):
        hi = 0.0
    elif lo < 0 < hi and plane.flat_empty_beyond_axis(f, False):
        lo = 0.0
    if lo < 0 < hi:
        raise ValueError(f"all points for rotate_extrude() must have the same X coordinate sign ({lo:.2f} -> {hi:.2f})")
    return (plane.flat_mirror(f), True) if hi <= 0 else (f, False)


def wedge_normals(angle, flip):
    """The outward normals of the half-spaces whose meet (up to 180
    degrees) or join cuts the turn from 0 to angle (from 180 on, flipped)."""
    sa, ca = meaning.sin_cos_deg(abs(angle))
    sg = -1.0 if angle < 0 else 1.0
    turn = -1.0 if flip else 1.0
    return [np.array([0.0, -sg, 0.0]) * turn, np.array([-sa, ca * sg, 0.0]) * turn]


def largest_stretch(A):
    """The largest singular value of a 2x2 matrix, as csgrt computes it."""
    (a, b), (c, d) = A
    f = a * a + b * b + c * c + d * d
    det = a * d - b * c
    return math.sqrt(0.5 * (f + math.sqrt(max(f * f - 4 * det * det, 0.0))))
