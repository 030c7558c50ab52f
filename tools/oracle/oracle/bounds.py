"""The faceting bounds: how far a mesh of n segments may stand off the exact
solid (derived in the package's text), per leaf and per face."""

import hashlib
import math

import numpy as np

from tools.oracle import scene as reader
from . import mesh

__all__ = ['COLOUR_TOLERANCE', 'CREASE', 'CROSS_SECTION_GRID', 'FP_ANGLE', 'GROW_SLACK', 'QUAD_SAMPLES', 'SHADOW_EDGES', 'SHADOW_EXTENT', 'SPHERE_FACTOR', 'bands', 'bezier_eval_rows', 'convex_parts', 'curvature_radius', 'ellipse_singular_values', 'extrusion_curvature', 'extrusion_face', 'extrusion_facets', 'extrusion_facets_of', 'face_class', 'facet_angle', 'facet_distance', 'feature_distance', 'feature_distances', 'features', 'hull_bridges', 'kite_reach', 'largest_radius', 'largest_radius_of', 'nearest_piece', 'object_point', 'quad_facets', 'quad_min_radius', 'quads', 'seed_of', 'seg_arrays', 'svg_slack', 'twist_surface', 'twisted_facets']


SPHERE_FACTOR = 3.0  # measured 2.69, rounded up
GROW_SLACK = 2  # pixels or rays of grid noise allowed when n doubles
COLOUR_TOLERANCE = 2  # bytes
FP_ANGLE = 1e-7  # radians


def seed_of(name):
    return int(hashlib.sha256(name.encode()).hexdigest()[:8], 16)


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
    R = mesh.flat_extent(p["flat"])
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
    slices, m = mesh.twist_steps(leaf, n)
    th = abs(math.radians(p["twist"]))
    sx, sy = p["scale2"]
    k, sg = max(abs(sx - 1), abs(sy - 1)), max(1.0, sx, sy)
    dt = 1.0 / slices
    pieces = mesh.section_pieces(mesh.refined(p["flat"], m), n)
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
        if isinstance(g, mesh.Arc):
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
        m = mesh.curve_steps(n)
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
        leaf._ellipse_sv = [np.linalg.svd(A, compute_uv=False) for A, _ in mesh.ellipses(leaf.params["flat"])]
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
    p, (smax, _) = leaf.params, mesh.svd(leaf)
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
    smax, smin = mesh.svd(leaf)
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
    p, (smax, _) = leaf.params, mesh.svd(leaf)
    r = {
        "sphere": lambda: p["r"],
        "cylinder": lambda: max(p["r1"], p["r2"], p["h"]),
        "torus": lambda: p["R"] + p["r"],
        "linear_extrude": lambda: max(mesh.flat_extent(p["flat"]) * max([1.0] + list(p.get("scale2") or [p["scale"]])), p["h"]),
        "rotate_extrude": lambda: mesh.flat_extent(p["flat"]),
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
        return min(curvature_radius(y, x) * mesh.svd(y)[1] ** 2 / mesh.svd(y)[0] for ops in convex_parts(leaf) for y in ops)
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


CREASE = 999_999


def nearest_piece(cand, slack):
    """The index of the least of `cand` (distances to smooth pieces: the
    two caps first, then the sides), or CREASE when it is a cap and the
    next a side or the other way round, within `slack` of each other: a
    point that near the rim may lie on either in a mesh whose surface
    moves by up to `slack` (the faceting distance), so the pixel is an
    edge. (Two sides meet at an angle the mesh keeps, or smoothly.)"""
    order = np.argsort(cand)
    if len(cand) > 2 and (order[0] < 2) != (order[1] < 2) and cand[order[1]] - cand[order[0]] <= slack:
        return CREASE
    return int(order[0])


def face_class(leaf, x, slack=0.0):
    """Which smooth piece of the leaf's surface world point x is on (see
    nearest_piece for `slack`: 0 a mesh's own crease)."""
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
        # In object units: the world slack over the smallest stretch.
        return nearest_piece(d, slack / mesh.svd(leaf)[1])
    if leaf.kind in reader.EXTRUSIONS:
        return extrusion_face(leaf, object_point(leaf, x), slack / mesh.svd(leaf)[1])
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
            polys = [np.asarray(l) for l in mesh.cross_section(f, 0).to_polygons()]
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
    own = [x for k in f[2] for x in features(k)]
    if f[0] == "op" and f[1] == "hull":
        return own + hull_bridges(f, own)
    return own


HULL_BRIDGES = {}


def hull_bridges(f, parts):
    """A 2-D hull's own edges, which lie on none of its parts' boundaries
    (a bridge from one part to the next): the edges of its fine mesh (4096
    segments a circle) whose midpoint is farther than 10^-6 of its size
    from every part's piece (computed once)."""
    if id(f) not in HULL_BRIDGES:
        polys = [np.asarray(l) for l in mesh.cross_section(f, 4096).to_polygons()]
        edges = [(l[i], l[(i + 1) % len(l)]) for l in polys for i in range(len(l))]
        pts = np.concatenate(polys) if polys else np.zeros((1, 2))
        tol = 1e-6 * max(1.0, float(np.abs(pts).max()))
        out = []
        if parts:
            arr = seg_arrays(parts)
            for a, b in edges:
                if min(feature_distances(arr, (a + b) / 2)) > tol:
                    out.append(("seg", a, b))
        HULL_BRIDGES[id(f)] = (f, out)
    return HULL_BRIDGES[id(f)][1]


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


def extrusion_face(leaf, q, slack=0.0):
    """Caps 0 and 1 (or the cuts of a partial turn), 2 + k the boundary
    piece k of the 2-D tree that the side over it comes from (CREASE
    within `slack` of two)."""
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
        return nearest_piece(cand, slack)
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
    return nearest_piece(cand, slack)


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
