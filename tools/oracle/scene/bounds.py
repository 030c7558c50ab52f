"""Bounds and the default camera: a leaf's and a node's world box, and the
framing of the scene's box."""

import math

import numpy as np

from . import meaning
from . import plane
from . import solids
from . import syntax

__all__ = ['EMPTY', 'EVERYTHING', 'UNIT', 'bounded_box', 'bounded_boxes', 'box', 'combine_boxes', 'cone_box', 'corner_box', 'extrusion_box', 'framing', 'framing_box', 'leaf_box']


# --------------------------------------------------------------------------
# Bounds and the default camera
# --------------------------------------------------------------------------

EVERYTHING = (np.full(3, -np.inf), np.full(3, np.inf))
EMPTY = (np.full(3, np.inf), np.full(3, -np.inf))
UNIT = (-np.ones(3), np.ones(3))


def leaf_box(leaf):
    """The exact world box of a leaf."""
    if leaf.kind == "hull":
        return combine_boxes("union", [leaf_box(x) for x in leaf.params["parts"]])
    if leaf.kind == "minkowski":
        # Supports add: so do boxes.
        bs = [combine_boxes("union", [leaf_box(x) for x in o]) for o in leaf.params["operands"]]
        return sum(b[0] for b in bs), sum(b[1] for b in bs)
    if leaf.kind in meaning.EXTRUSIONS:
        return extrusion_box(leaf)
    m, p = leaf.matrix, leaf.params
    if leaf.kind == "polyhedron":
        # The box of the placed vertices (of the faces; a point no face
        # uses is not part of the solid).
        used = sorted({i for f in p["faces"] for i in f})
        w = p["points"][used] @ m[:3, :3].T + m[:3, 3]
        return w.min(axis=0), w.max(axis=0)
    L, t = m[:3, :3], m[:3, 3]
    row = lambda cols: np.sqrt(sum(L[:, c] ** 2 for c in cols))
    if leaf.kind == "sphere":
        e = p["r"] * row([0, 1, 2])
        return t - e, t + e
    if leaf.kind == "torus":
        e = p["R"] * row([0, 1]) + p["r"] * row([0, 1, 2])
        return t - e, t + e
    if leaf.kind == "cylinder":
        z0 = -p["h"] / 2 if p["center"] else 0.0
        e = row([0, 1])
        c0, c1 = L @ [0, 0, z0] + t, L @ [0, 0, z0 + p["h"]] + t
        return np.minimum(c0 - e * p["r1"], c1 - e * p["r2"]), np.maximum(c0 + e * p["r1"], c1 + e * p["r2"])
    if leaf.kind == "cube":
        s = p["size"]
        lo = -s / 2 if p["center"] else np.zeros(3)
        corners = [L @ (lo + s * np.array([(i >> k) & 1 for k in range(3)])) + t for i in range(8)]
        return np.min(corners, axis=0), np.max(corners, axis=0)
    # halfspace n.x <= offset: bounded on one side when axis-aligned
    n = np.linalg.inv(L).T @ p["normal"]
    lo, hi = EVERYTHING[0].copy(), EVERYTHING[1].copy()
    nz = [i for i in range(3) if n[i] != 0]
    if len(nz) == 1:
        q = L @ (p["normal"] * p["offset"] / (p["normal"] @ p["normal"])) + t
        i = nz[0]
        if n[i] > 0:
            hi[i] = q[i]
        else:
            lo[i] = q[i]
    return lo, hi


def combine_boxes(op, bs):
    if op in ("union", "xor", "hull"):
        return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)
    if op == "intersection":
        return np.max([b[0] for b in bs], axis=0), np.min([b[1] for b in bs], axis=0)
    return bs[0]


def corner_box(m, lo, hi):
    corners = [m[:3, :3] @ np.where([(i >> k) & 1 for k in range(3)], hi, lo) + m[:3, 3] for i in range(8)]
    return np.min(corners, axis=0), np.max(corners, axis=0)


def cone_box(m, A, c, s, z0, h):
    """The exact box of the cone over the ellipse A x + c (z = z0) tapered
    by s to z0 + h, placed by m: the hull of its two ellipses."""
    L, t = m[:3, :3], m[:3, 3]
    out = []
    for k, z in ((1.0, z0), (s, z0 + h)):
        C = L @ np.array([k * c[0], k * c[1], z]) + t
        U, V = L @ np.array([k * A[0, 0], k * A[1, 0], 0.0]), L @ np.array([k * A[0, 1], k * A[1, 1], 0.0])
        e = np.sqrt(U**2 + V**2)
        out.append((C - e, C + e))
    return combine_boxes("union", out)


def extrusion_box(leaf):
    """The box of an extrusion, as csgrt frames it: the box of the solid
    each 2-D leaf sweeps (a prism's corners; a cone over an ellipse, a torus
    or an ellipsoid exactly), combined as the 2-D tree combines them."""
    m, p = leaf.matrix, leaf.params
    L, t = m[:3, :3], m[:3, 3]
    if leaf.kind == "linear_extrude" and solids.twisted(p):
        # csgrt's box of a twisted or unevenly scaled prism: without twist,
        # each axis scaled at the top; with it, the disc of the farthest
        # vertex grown by the larger of 1 and each scale. A centred circle
        # is the cone it sweeps.
        h, z0, (sx, sy) = p["h"], p["z0"], p["scale2"]
        grow = np.array([max(1.0, sx), max(1.0, sy)])

        def rec(f):
            if f[0] == "op" and f[1] == "hull" and (hp := plane.hull_polygon(f)) is not None:
                return rec(hp)
            if f[0] == "poly":
                pts = np.concatenate(f[1])
                if p["twist"] == 0:
                    lo, hi = pts.min(axis=0), pts.max(axis=0)
                    lo, hi = np.minimum(lo, lo * [sx, sy]), np.maximum(hi, hi * [sx, sy])
                else:
                    rho = float(np.max(np.hypot(pts[:, 0], pts[:, 1])))
                    lo, hi = -grow * rho, grow * rho
                return corner_box(m, np.array([lo[0], lo[1], z0]), np.array([hi[0], hi[1], z0 + h]))
            if f[0] == "ellipse":
                A, c = f[1], f[2]
                if sx == sy and (p["twist"] == 0 or plane.is_circle(A) and not np.any(c)):
                    return cone_box(m, A, c, sx, z0, h)
                # As csgrt's twisted ellipse: its box, or the disc of its
                # farthest point |c| + the largest singular value.
                if p["twist"] == 0:
                    e = np.sqrt(A[:, 0] ** 2 + A[:, 1] ** 2)
                    lo, hi = c - e, c + e
                    lo, hi = np.minimum(lo, lo * [sx, sy]), np.maximum(hi, hi * [sx, sy])
                else:
                    rho = math.hypot(c[0], c[1]) + solids.largest_stretch(A)
                    lo, hi = -grow * rho, grow * rho
                return corner_box(m, np.array([lo[0], lo[1], z0]), np.array([hi[0], hi[1], z0 + h]))
            return combine_boxes(f[1], [rec(k) for k in f[2]])

        return rec(p["flat"])
    if leaf.kind == "linear_extrude":
        h, z0, s = p["h"], p["z0"], p["scale"]

        def rec(f):
            if f[0] == "op" and f[1] == "hull" and (hp := plane.hull_polygon(f)) is not None:
                return rec(hp)
            if f[0] == "framed":
                return corner_box(m, np.array([f[2][0], f[2][1], z0]), np.array([f[3][0], f[3][1], z0 + h]))
            if f[0] in ("poly", "curves"):
                if f[0] == "poly":
                    pts = np.concatenate(f[1])
                    lo, hi = pts.min(axis=0), pts.max(axis=0)
                else:
                    lo, hi = plane.curve_extent(f)
                lo, hi = np.minimum(lo, lo * s), np.maximum(hi, hi * s)
                return corner_box(m, np.array([lo[0], lo[1], z0]), np.array([hi[0], hi[1], z0 + h]))
            if f[0] == "ellipse":
                return cone_box(m, f[1], f[2], s, z0, h)
            return combine_boxes(f[1], [rec(k) for k in f[2]])

        return rec(p.get("frame", p["flat"]))
    f, flip = solids.revolve_setup(p)

    def rec(f):
        if f[0] == "op" and f[1] == "hull" and (hp := plane.hull_polygon(f)) is not None:
            return rec(hp)
        if f[0] == "curves":
            # Wholly at x >= 0 (the axis rule): its exact box, turned.
            lo, hi = plane.curve_extent(f)
            r = max(hi[0], 0.0)
            return corner_box(m, np.array([-r, -r, lo[1]]), np.array([r, r, hi[1]]))
        if f[0] == "poly":
            loops = plane.clip_right(f[1])
            if not loops:
                return EMPTY
            pts = np.concatenate(loops)
            r = max(pts[:, 0].max(), 0.0)
            return corner_box(m, np.array([-r, -r, pts[:, 1].min()]), np.array([r, r, pts[:, 1].max()]))
        if f[0] == "ellipse" and (f[1][0, 1] != 0 or f[1][1, 0] != 0):
            # A slanted ellipse (wholly on one side): its reach along x and z.
            A, c = f[1], f[2]
            ex, ez = math.hypot(A[0, 0], A[0, 1]), math.hypot(A[1, 0], A[1, 1])
            if c[0] + ex <= 0:
                return EMPTY
            r = c[0] + ex
            return corner_box(m, np.array([-r, -r, c[1] - ez]), np.array([r, r, c[1] + ez]))
        if f[0] == "ellipse":
            A, c = f[1], f[2]
            ra, rz = abs(A[0, 0]), abs(A[1, 1])
            if c[0] + ra <= 0:
                return EMPTY
            st = syntax.Stmt("x", [], [], "", 0, 0)
            if c[0] == 0:
                lf = meaning.Leaf("sphere", dict(r=1.0), m @ meaning.affine(np.diag([ra, ra, rz]), [0, 0, c[1]]), {}, st)
            else:
                lf = meaning.Leaf("torus", dict(R=1.0, r=ra / c[0]), m @ meaning.affine(np.diag([c[0], c[0], c[0] * rz / ra]), [0, 0, c[1]]), {}, st)
            return leaf_box(lf)
        return combine_boxes(f[1], [rec(k) for k in f[2]])

    b = rec(f)
    if p["angle"] != 360:
        st = syntax.Stmt("x", [], [], "", 0, 0)
        hs = [leaf_box(meaning.Leaf("halfspace", dict(normal=n, offset=0.0), m, {}, st)) for n in solids.wedge_normals(p["angle"], flip)]
        w = combine_boxes("intersection" if abs(p["angle"]) <= 180 else "union", hs)
        b = combine_boxes("intersection", [b, w])
    return b


def box(node):
    if node is None:
        return EMPTY
    if isinstance(node, meaning.Leaf):
        return leaf_box(node)
    bs = [box(c) for c in node.children]
    if node.op == "union":
        return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)
    if node.op == "intersection":
        return np.max([b[0] for b in bs], axis=0), np.min([b[1] for b in bs], axis=0)
    return bs[0]


def bounded_boxes(scene):
    """The world boxes of the leaves that have finite ones (not a halfspace)."""
    boxes = [leaf_box(x) for x in scene.leaves]
    return [b for b in boxes if np.all(np.isfinite(b[0])) and np.all(np.isfinite(b[1]))]


def bounded_box(scene, default=EMPTY):
    """The union of [`bounded_boxes`], or `default` when there are none."""
    boxes = bounded_boxes(scene)
    if not boxes:
        return default
    return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)


def framing_box(scene):
    lo, hi = box(scene.root)
    if np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) or np.any(lo > hi):
        return lo, hi
    return bounded_box(scene)


def framing(scene, width, height, framed=None, fov=30.0, fill=0.9):
    lo, hi = framing_box(scene) if framed is None else framed
    if np.any(lo > hi) or not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        lo, hi = -np.ones(3), np.ones(3)
    center = (lo + hi) / 2
    ax, az = math.radians(55), math.radians(25)
    back = np.array([math.sin(ax) * math.sin(az), -math.sin(ax) * math.cos(az), math.cos(ax)])
    fwd = -back
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    tan_h = math.tan(math.radians(fov) / 2) * fill
    tan_v = tan_h * height / width
    dist = 0.5 * np.linalg.norm(hi - lo) * 1.01
    for i in range(8):
        c = np.where([(i >> k) & 1 for k in range(3)], hi, lo) - center
        depth = c @ fwd
        dist = max(dist, abs(c @ right) / tan_h - depth, abs(c @ up) / tan_v - depth)
    dist = max(dist, 1e-9)
    return center + back * dist, center, np.array([0.0, 0.0, 1.0]), fov
