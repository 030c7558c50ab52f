"""Meshing: each leaf of the reader's tree as a manifold3d mesh of n segments
(extrusions through their cross-sections, polyhedra, hulls)."""

import itertools
import math

import manifold3d as mf
import numpy as np

from tools.oracle import scene as reader
from . import bounds

__all__ = ['Arc', 'Line', 'arc_sweep', 'circle_pieces', 'convex_solid', 'cross_section', 'curve_steps', 'drawing_pieces', 'ellipses', 'extrusion_mesh', 'flat_extent', 'flatten_curves', 'has_hull', 'leaf_mesh', 'polyhedron_solid', 'polyhedron_triangles', 'refined', 'section_pieces', 'svd', 'svg_loop_points', 'twist_steps']


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
    """(A, centre, start angle, sweep) of a drawing's arc of the ellipse
    c + A (cos w, sin w) from a to b through its middle point (either way
    round), the angles those of the ellipse's parameter."""
    A, c, mid = arc
    inv = np.linalg.inv(A)
    w = lambda p: math.atan2(*(inv @ (p - c))[::-1])
    a0, am, a1 = w(a), w(mid), w(b)
    ccw = (am - a0) % (2 * math.pi) < (a1 - a0) % (2 * math.pi) or abs(a1 - a0) < 1e-15
    sweep = (a1 - a0) % (2 * math.pi) if ccw else -((a0 - a1) % (2 * math.pi))
    return A, c, a0, sweep if sweep != 0 else 2 * math.pi


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
    _, paths, ellipses = f[3]
    loops = []
    for path in paths:
        pieces = []
        for i, (a, arc) in enumerate(path):
            b = path[(i + 1) % len(path)][0]
            if arc is None:
                pieces.append(Line(a, b))
                continue
            A, c, a0, sweep = arc_sweep(a, arc, b)
            k = max(1, math.ceil(abs(sweep) / (2 * math.pi / n)))
            pieces += [Arc(A, c, a0 + sweep * j / k, sweep / k, a if j == 0 else None) for j in range(k)]
        loops.append(pieces)
    for A, c in ellipses:
        loops.append(circle_pieces(A, c, n))
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
        _, paths, ellipses = f[3]
        cut = []
        for path in paths:
            out = []
            for i, (a, arc) in enumerate(path):
                out.append((a, arc))
                if arc is None:
                    b = path[(i + 1) % len(path)][0]
                    out += [((1 - j / m) * a + j / m * b, None) for j in range(1, m)]
            cut.append(out)
        return ("op", f[1], [refined(k, m) for k in f[2]], ("drawing", cut, ellipses))
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
        if id(f) not in bounds.SHADOW_EXTENT:
            bounds.SHADOW_EXTENT[id(f)] = (f, float(np.abs(np.concatenate(f[1])).max()))
        return bounds.SHADOW_EXTENT[id(f)][1]
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
