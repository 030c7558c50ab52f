"""2-D figures: moving, offsetting, summing, hulls, insides, curves and
extents of the 2-D trees the statements below extrusions make."""

import math

import numpy as np

from . import meaning
from . import solids
from . import svg

__all__ = ['bezier_eval', 'bezier_points', 'bezier_turning', 'boundary_strokes', 'boxes_apart', 'clip_right', 'convex_hull_2d', 'convex_parts', 'convex_poly', 'curve_extent', 'curve_pieces', 'curved_offset_pieces', 'edges_and_circles', 'even_odd_inside', 'flat_inside', 'flat_mirror', 'flat_moved', 'flat_stmt', 'flat_x_range', 'grown_convex', 'has_section', 'hull_polygon', 'is_circle', 'join_piece', 'minkowski_flat', 'offset_pieces', 'outline_box', 'outward_normals', 'plain_op', 'sector_pieces', 'straight_loops', 'sum_choices', 'swept_pieces', 'translation_2d']


def flat_moved(f, m):
    """A 2-D tree moved by the plane matrix m (3x3, homogeneous)."""
    if f[0] in ("section", "shadow"):
        return (f[0], f[1], m @ f[2], f[3])
    if f[0] == "faces":
        return ("faces", [solids.ccw(l @ m[:2, :2].T + m[:2, 2]) for l in f[1]])
    if f[0] == "poly":
        return ("poly", [l @ m[:2, :2].T + m[:2, 2] for l in f[1]])
    if f[0] == "ellipse":
        return ("ellipse", m[:2, :2] @ f[1], m[:2, :2] @ f[2] + m[:2, 2])
    if f[0] == "curves":
        # A control is one point (quadratic) or two (cubic, a 2 x 2 array).
        mv = lambda q: None if q is None else q @ m[:2, :2].T + m[:2, 2]
        return ("curves", [[(mv(q), mv(c)) for q, c in l] for l in f[1]])
    if len(f) == 4 and f[3][0] == "svg":
        moved = [(m @ g, [svg.part_moved(x, m) for x in parts], sl) for g, parts, sl in f[3][1]]
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("svg", moved))
    if len(f) == 4 and f[3][0] == "drawing":
        _, paths, ellipses = f[3]
        mv = lambda q: m[:2, :2] @ q + m[:2, 2]
        arc = lambda x: None if x is None else (m[:2, :2] @ x[0], mv(x[1]), mv(x[2]))
        moved = ([[(mv(p), arc(x)) for p, x in path] for path in paths], [(m[:2, :2] @ A, mv(c)) for A, c in ellipses])
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("drawing",) + moved)
    if len(f) == 4 and f[3][0] == "bands":
        # Distances scale with a similarity's factor.
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("bands", f[3][1] * math.sqrt(abs(np.linalg.det(m[:2, :2])))))
    if len(f) == 4 and f[3][0] == "kites":
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("kites", f[3][1] * float(np.linalg.norm(m[:2, :2], 2))))
    if len(f) == 4:
        join, d, child, m0 = f[3]
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], (join, d, child, m @ m0))
    return ("op", f[1], [flat_moved(k, m) for k in f[2]])


def outward_normals(loop, loops):
    """Each edge's unit outward normal (the even-odd region is not on its
    side just off the edge's middle)."""
    from_pts = np.asarray(loop)
    out = []
    size = max(float(np.abs(np.concatenate(loops)).max()), 1e-300)
    for i in range(len(from_pts)):
        a, b = from_pts[i], from_pts[(i + 1) % len(from_pts)]
        e = b - a
        n = np.array([e[1], -e[0]]) / np.linalg.norm(e)
        mid = (a + b) / 2 + n * 1e-9 * size
        out.append(-n if even_odd_inside(loops, mid) else n)
    return out


def even_odd_inside(loops, p):
    inside = False
    for l in loops:
        for a, b in zip(l, np.roll(l, -1, axis=0)):
            if (a[1] > p[1]) != (b[1] > p[1]):
                x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                inside ^= x > p[0]
    return inside


def straight_loops(f):
    """The loops of the boundary of a 2-D tree of straight polygons (union,
    intersection, difference), by manifold's boolean (Clipper2's, on its
    grid of 1e-8); None for a tree with other leaves."""

    def straight(g):
        return g[0] == "poly" or g[0] == "op" and len(g) == 3 and g[1] in ("union", "intersection", "difference") and all(map(straight, g[2]))

    if not straight(f):
        return None
    import manifold3d as mf

    def cs(g):
        if g[0] == "poly":
            return mf.CrossSection([l.tolist() for l in g[1]], mf.FillRule.EvenOdd)
        kids = [cs(k) for k in g[2]]
        if g[1] == "union":
            return mf.CrossSection.batch_boolean(kids, mf.OpType.Add)
        if g[1] == "intersection":
            return mf.CrossSection.batch_boolean(kids, mf.OpType.Intersect)
        return kids[0] - mf.CrossSection.batch_boolean(kids[1:], mf.OpType.Add)

    return [np.asarray(l, dtype=float) for l in cs(f).to_polygons()]


def offset_pieces(f, join, d):
    """OpenSCAD's offset of a 2-D tree as the CSG of plain 2-D leaves it
    is (Clipper's joins: round = the disc of radius |d| at a corner, miter =
    the kite to the two offset edges' meeting point, square = that kite cut
    across the corner's bisector at distance |d|): growing a simple polygon
    is it, the band each edge sweeps moving out by d, and a join at each
    convex corner; shrinking is it minus the bands swept inward and the
    joins at its reflex corners. A circle grows to radius R + d. Growing
    maps over a union, shrinking over an intersection; anything else is
    not in the oracle."""
    if f[0] == "op":
        # Shrinking a union of shapes whose boxes are apart: each by itself
        # (a disc inside a union of disjoint closed sets lies in one).
        apart = f[1] == "union" and d < 0 and boxes_apart(f[2])
        if f[1] == "union" and (d > 0 or apart) or f[1] == "intersection" and d < 0:
            parts = [offset_pieces(k, join, d) for k in f[2]]
            if f[1] == "intersection" and any(p is None for p in parts):
                return None
            parts = [p for p in parts if p is not None]
            return None if not parts else parts[0] if len(parts) == 1 else ("op", f[1], parts)
        loops = straight_loops(f)
        if loops is None:
            swept = swept_pieces(f, join, d)
            if swept is None:
                raise ValueError(f"offset of a 2-D {f[1]} by {d:g} is not in the oracle")
            return swept
        # Any other combination of straight polygons: its boundary's loops
        # (manifold's boolean), offset as one polygon.
        return offset_pieces(("poly", loops), join, d) if loops else None
    if f[0] == "ellipse":
        A = f[1]
        r = math.hypot(A[0, 0], A[1, 0])
        if abs(A[:, 0] @ A[:, 1]) > 1e-12 * r * r or abs(math.hypot(A[0, 1], A[1, 1]) - r) > 1e-12 * r:
            raise ValueError("offset of an ellipse is not in the oracle")
        return ("ellipse", np.eye(2) * (r + d), f[2]) if r + d > 0 else None
    if f[0] == "curves":
        return curved_offset_pieces(f, join, d)
    # A repeated point makes an edge of no length: left out (and a loop
    # left with fewer than 3 points, unless none is left).
    kept = [np.asarray([l[i] for i in range(len(l)) if np.any(l[i] != l[(i + 1) % len(l)])], float) for l in f[1]]
    kept = [l for l in kept if len(l) >= 3]
    loops = kept if kept else f[1]
    if meets_itself(loops):
        # Read by parity (as OpenSCAD sanitizes a polygon): swept along
        # its boundary's strokes, cut where it meets itself.
        return swept_pieces(("poly", loops), join, d, straight=True)
    k, side = abs(d), (1.0 if d > 0 else -1.0)
    pieces = []
    for l in loops:
        ns = outward_normals(l, loops)
        m = len(l)
        for i in range(m):
            a, v, b = l[(i - 1) % m], l[i], l[(i + 1) % m]
            n1, n2 = ns[(i - 1) % m] * side, ns[i] * side
            pieces.append(("poly", [np.array([v, b, b + k * n2, v + k * n2])]))
            t1, t2 = v - a, b - v
            if (t2 @ n1) >= 0 or t1[0] * t2[1] - t1[1] * t2[0] == 0:
                continue  # no join where the offset side sees the corner reflex
            pieces.append(join_piece(join, v, n1, n2, t1, t2, k))
    body = ("poly", loops)
    return ("op", "union" if d > 0 else "difference", [body] + pieces)


def meets_itself(loops, most=2000):
    """Whether two edges of `loops` that are not neighbours in one loop
    meet (cross, touch or overlap); outlines of more than `most` edges are
    taken as simple (the test is quadratic)."""
    ends = [(np.asarray(l[i], float), np.asarray(l[(i + 1) % len(l)], float)) for l in loops for i in range(len(l))]
    n = len(ends)
    if n > most:
        return False
    A = np.array([e[0] for e in ends])
    B = np.array([e[1] for e in ends])
    a, b, c, e = A[:, None], B[:, None], A[None], B[None]
    turn = lambda p, q, r: (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])
    hit = (turn(a, b, c) * turn(a, b, e) <= 0) & (turn(c, e, a) * turn(c, e, b) <= 0)
    for k in (0, 1):
        hit &= (np.minimum(a[..., k], b[..., k]) <= np.maximum(c[..., k], e[..., k])) & (np.minimum(c[..., k], e[..., k]) <= np.maximum(a[..., k], b[..., k]))
    start = 0
    for l in loops:
        m = len(l)
        for i in range(m):
            j = start + (i + 1) % m
            hit[start + i, j] = hit[j, start + i] = False
        start += m
    np.fill_diagonal(hit, False)
    return bool(hit.any())


def plain_op(g):
    """Whether g is a union, intersection, difference or parity (a
    drawing's) of 2-D trees (an offset's pieces are one too)."""
    return g[0] == "op" and g[1] in ("union", "intersection", "difference", "xor") and (len(g) == 3 or len(g) == 4 and g[3][0] in ("round", "miter", "square", "kites", "drawing"))


def edges_and_circles(f, combines):
    """The polygon edges (a, b) and circles (c, r) of a 2-D tree whose
    combinations pass `combines`; None for another leaf."""
    segs, circles = [], []

    def leaves(g):
        if g[0] == "poly":
            segs.extend((np.asarray(l[i], float), np.asarray(l[(i + 1) % len(l)], float)) for l in g[1] for i in range(len(l)))
            return True
        if g[0] == "ellipse":
            if not is_circle(g[1]):
                return False
            circles.append((np.asarray(g[2], float), float(np.linalg.norm(g[1][:, 0]))))
            return True
        return combines(g) and all(leaves(k) for k in g[2])

    return (segs, circles) if leaves(f) else None


def boundary_strokes(f, straight=False):
    """The boundary of a 2-D tree of straight polygons and circles as
    strokes with the region on their left — ("line", p, q) and ("arc", c,
    r, a0, span, convex): the circle's angles a0 to a0 + span, the region
    on the centre's side when convex — and the distance within which two
    points are one; None for other leaves. Each polygon edge is cut where
    any other edge or circle crosses it, each circle where anything
    crosses it, and a piece kept where the region is on exactly one of its
    sides, 1e-9 of the tree's size off the piece's middle."""
    got = edges_and_circles(f, plain_op)
    if got is None or not (got[1] or straight):
        return None
    segs, circles = got
    size = max([float(np.abs(q).max()) for sg in segs for q in sg] + [float(np.abs(c).max()) + r for c, r in circles])
    eps = 1e-9 * size
    inside = lambda q: bool(flat_inside(f, q))

    def seg_circle(a, b, c, r):
        d = b - a
        A, B, C = d @ d, 2 * (a - c) @ d, (a - c) @ (a - c) - r * r
        disc = B * B - 4 * A * C
        if A == 0 or disc < 0:
            return []
        return [u for u in ((-B - math.sqrt(disc)) / (2 * A), (-B + math.sqrt(disc)) / (2 * A)) if 0 <= u <= 1]

    out = []
    for i, (a, b) in enumerate(segs):
        d = b - a
        if not np.any(d):
            continue
        us = [0.0, 1.0]
        for j, (p0, q0) in enumerate(segs):
            e = q0 - p0
            den = d[0] * e[1] - d[1] * e[0]
            if j == i:
                continue
            if abs(den) <= 1e-12 * np.linalg.norm(d) * np.linalg.norm(e):
                # Along the same line: cut at the other edge's ends.
                off = lambda x: abs((x - a)[0] * d[1] - (x - a)[1] * d[0]) / np.linalg.norm(d)
                if off(p0) <= eps and off(q0) <= eps:
                    us += [float((p0 - a) @ d / (d @ d)), float((q0 - a) @ d / (d @ d))]
                continue
            w = p0 - a
            u, v = (w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den
            if 0 <= u <= 1 and 0 <= v <= 1:
                us.append(u)
        for c, r in circles:
            us += seg_circle(a, b, c, r)
        us = sorted(u for u in us if 0 <= u <= 1)
        nrm = np.array([-d[1], d[0]]) / np.linalg.norm(d)
        for u0, u1 in zip(us, us[1:]):
            if u1 > u0:
                mid = a + (u0 + u1) / 2 * d
                left, right = inside(mid + eps * nrm), inside(mid - eps * nrm)
                if left != right:
                    p0, p1 = a + u0 * d, a + u1 * d
                    out.append(("line", p0, p1) if left else ("line", p1, p0))
    for i, (c, r) in enumerate(circles):
        angs = []
        for a, b in segs:
            angs += [math.atan2(*(a + u * (b - a) - c)[::-1]) for u in seg_circle(a, b, c, r)]
        for j, (c2, r2) in enumerate(circles):
            dd = c2 - c
            l = float(np.linalg.norm(dd))
            if j != i and 0 < l <= r + r2 and l >= abs(r - r2):
                x = (r * r - r2 * r2 + l * l) / (2 * l)
                h = math.sqrt(max(r * r - x * x, 0.0))
                mid, perp = c + dd * x / l, np.array([-dd[1], dd[0]]) / l
                angs += [math.atan2(*(q - c)[::-1]) for q in (mid + h * perp, mid - h * perp)]
        angs = sorted(angs)
        spans = [(a0, a1 - a0) for a0, a1 in zip(angs, angs[1:] + [angs[0] + 2 * math.pi]) if a1 > a0] if angs else [(0.0, 2 * math.pi)]
        for a0, span in spans:
            u = np.array([math.cos(a0 + span / 2), math.sin(a0 + span / 2)])
            outer, inner = inside(c + (r + eps) * u), inside(c + (r - eps) * u)
            if outer != inner:
                out.append(("arc", c, r, a0, span, inner))
    return out, eps


def swept_pieces(f, join, d, straight=False):
    """Any other offset of a 2-D tree of polygons and circles, from its
    boundary's strokes: R grown is R with every point within |d| of its
    boundary, R shrunk is R without them; the points within |d| of a line
    stroke are its two-sided band and a disc at each end, of an arc the
    annular sector over its angles (radii r -+ |d|) and the same discs.
    Miter and square joins add (take away) the kite at each corner the
    offset side sees as convex. None for other leaves."""
    got = boundary_strokes(f, straight)
    if got is None:
        return None
    strokes, tol = got
    k, side = abs(d), (1.0 if d > 0 else -1.0)
    pieces, ends = [f], []

    def ends_of(st):
        if st[0] == "line":
            return st[1], st[2]
        _, c, r, a0, span, convex = st
        p0, p1 = (c + r * np.array([math.cos(a), math.sin(a)]) for a in (a0, a0 + span))
        return (p0, p1) if convex else (p1, p0)

    def tangent(st, at_end):
        if st[0] == "line":
            t = st[2] - st[1]
            return t / np.linalg.norm(t)
        _, c, r, a0, span, convex = st
        a = a0 + span if convex == at_end else a0
        t = np.array([-math.sin(a), math.cos(a)])
        return t if convex else -t

    for st in strokes:
        if st[0] == "line":
            p0, p1 = st[1], st[2]
            t = p1 - p0
            n = np.array([-t[1], t[0]]) * (k / np.linalg.norm(t))
            pieces.append(("poly", [np.array([p0 - n, p1 - n, p1 + n, p0 + n])]))
        else:
            _, c, r, a0, span, _ = st
            pieces += sector_pieces(c, r - k, r + k, a0, span)
            if span >= 2 * math.pi:
                continue
        for e in ends_of(st):
            if all(np.linalg.norm(x - e) > tol for x in ends):
                ends.append(e)
    pieces += [("ellipse", np.eye(2) * k, e.copy()) for e in ends]
    if join != "round":
        kites, reach = [], 0.0
        # Corners join the strokes that are not whole circles, not within
        # 1000 tol long (slivers where a band's edge meets a circle
        # tangent), and not copies of another: the next stroke starts
        # nearest the end, within 1000 tol; two within tol touch.
        slack, chain = 1e3 * tol, []
        for st in strokes:
            p0, p1 = ends_of(st)
            whole = st[0] == "arc" and st[4] >= 2 * math.pi
            copy = any(np.linalg.norm(ends_of(o)[0] - p0) <= tol and np.linalg.norm(ends_of(o)[1] - p1) <= tol for o in chain)
            if not whole and np.linalg.norm(p1 - p0) > slack and not copy:
                chain.append(st)
        for st in chain:
            v = ends_of(st)[1]
            nxt = sorted((float(np.linalg.norm(ends_of(o)[0] - v)), i) for i, o in enumerate(chain))
            nxt = [x for x in nxt if x[0] <= slack]
            # Those within tol along one direction overlap: any one serves.
            one_way = nxt and all(np.linalg.norm(tangent(chain[i], False) - tangent(chain[nxt[0][1]], False)) <= 1e-9 for l, i in nxt if l <= tol)
            if not nxt:
                raise ValueError("a sharp offset of an outline that does not close is not in the oracle")
            pick = nxt[0][1]
            if len(nxt) > 1 and nxt[1][0] <= tol and not one_way:
                # The boundary meets itself at v: the corner is the one of
                # the loop st runs on (Clipper joins each loop's own), the
                # stroke out of v that bounds the same wedge of the offset
                # side — the least turn from the way back along st,
                # clockwise when grown (the shape's wedge), counter-
                # clockwise when shrunk (the outside's).
                back = -tangent(st, True)

                def turn(i):
                    t = tangent(chain[i], False)
                    a = (math.atan2(back[1], back[0]) - math.atan2(t[1], t[0])) * side
                    return a % (2 * math.pi) or 2 * math.pi

                pick = min((i for l, i in nxt if l <= tol), key=turn)
            t1, t2 = tangent(st, True), tangent(chain[pick], False)
            n1, n2 = np.array([t1[1], -t1[0]]) * side, np.array([t2[1], -t2[0]]) * side
            if t2 @ n1 >= 0 or 1 - n1 @ n2 <= 1e-12:
                continue
            kites.append(join_piece(join, v, n1, n2, t1, t2, k))
            reach = max(reach, max(float(np.linalg.norm(q - v)) for q in kites[-1][1][0]))
        if kites:
            # Marked with their reach: a flattened circle's last chord
            # turns a kite's side about its corner (tools/oracle/oracle/).
            pieces.append(("op", "union", kites, ("kites", reach)))
    return ("op", "union" if d > 0 else "difference", pieces)


def sector_pieces(c, r0, r1, a0, span):
    """The annular sector about c between radii r0 (none below 0) and r1
    over the angles a0 to a0 + span as 2-D trees: a ring for a whole turn,
    else sectors of at most a half turn, each the disc r1 met with its
    wedge cut to the sector's exact box (csgrt's framing), less disc r0."""
    disc = lambda r: ("ellipse", np.eye(2) * r, np.asarray(c, float).copy())
    hole = lambda g: ("op", "difference", [g, disc(r0)]) if r0 > 0 else g
    if span >= 2 * math.pi:
        return [hole(disc(r1))]
    m = max(1, math.ceil(span / math.pi))
    at = lambda a, r: c + r * np.array([math.cos(a), math.sin(a)])
    out = []
    for i in range(m):
        b0 = a0 + span * i / m
        b1 = b0 + span / m
        pts = [at(b0, r1), at(b1, r1)] + ([at(b0, r0), at(b1, r0)] if r0 > 0 else [np.asarray(c, float)])
        pts += [at(q * math.pi / 2, r1) for q in range(-4, 10) if b0 < q * math.pi / 2 < b1]
        lo, hi = np.min(pts, axis=0), np.max(pts, axis=0)
        wedge = [np.asarray(c, float), at(b0, 2 * r1), at((b0 + b1) / 2, 2 * r1), at(b1, 2 * r1)]
        # The wedge met with the box: cut by each of its four sides.
        for axis, bound, sign in ((0, lo[0], 1), (0, hi[0], -1), (1, lo[1], 1), (1, hi[1], -1)):
            cut = []
            for j, q0 in enumerate(wedge):
                q1 = wedge[(j + 1) % len(wedge)]
                s0, s1 = (q0[axis] - bound) * sign, (q1[axis] - bound) * sign
                if s0 >= 0:
                    cut.append(q0)
                if (s0 >= 0) != (s1 >= 0):
                    cut.append(q0 + (q1 - q0) * (s0 / (s0 - s1)))
            wedge = cut
        if len(wedge) >= 3:
            out.append(hole(("op", "intersection", [disc(r1), ("poly", [np.array(wedge)])])))
    return out


def outline_box(f):
    """A box (lo, hi) holding a 2-D tree (its leaves' points and control
    points; a combination's, all of its leaves'), or None for a projection."""
    if f[0] in ("poly", "faces"):
        pts = np.concatenate([np.asarray(l, float) for l in f[1]])
        return pts.min(axis=0), pts.max(axis=0)
    if f[0] == "curves":
        pts = np.array([q for l in f[1] for e in l for q in ([e[0]] + ([] if e[1] is None else list(np.asarray(e[1], float).reshape(-1, 2))))], float)
        return pts.min(axis=0), pts.max(axis=0)
    if f[0] == "ellipse":
        h = np.array([math.hypot(f[1][0, 0], f[1][0, 1]), math.hypot(f[1][1, 0], f[1][1, 1])])
        return f[2] - h, f[2] + h
    if f[0] != "op":
        return None
    bs = [outline_box(k) for k in f[2]]
    if any(b is None for b in bs):
        return None
    return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)


def boxes_apart(kids):
    """Whether no two of the 2-D trees' boxes meet."""
    bs = [outline_box(k) for k in kids]
    if any(b is None for b in bs):
        return False
    for i in range(len(bs)):
        for j in range(i + 1, len(bs)):
            (a0, a1), (b0, b1) = bs[i], bs[j]
            if np.all(b0 <= a1) and np.all(a0 <= b1):
                return False
    return True


def curved_offset_pieces(f, join, d):
    """A curved outline (a glyph's quadratic edges) offset by d: the points
    within |d| of it (grown) or of the inside farther than |d| from it
    (shrunk), whose boundary lies at |d| from the edges — on the curves
    their points trace along their normals and the circles about their
    ends. The oracle meshes manifold's own offset of the flattened outline
    (cross_section); these pieces carry the bounds and the faces: the
    outline, marked ("bands", |d|) (its edges' faces lie |d| from them),
    a disc at each corner, and with miter or square joins the kite (or cut
    kite) at each sharp corner that the offset side sees as convex."""
    k, side = abs(d), (1.0 if d > 0 else -1.0)
    if any(c is not None and np.asarray(c).ndim == 2 for _, c, _ in curve_pieces(f)):
        raise ValueError("offset of cubic curves is not in the oracle")
    fine = [np.concatenate([bezier_eval(bezier_points(l[i][0], l[i][1], l[(i + 1) % len(l)][0]), np.arange(64) / 64) for i in range(len(l))]) for l in f[1]]
    size = max(float(np.abs(np.concatenate(fine)).max()), 1e-300)

    def outward(P, u, t):
        # The unit normal at B(u) on the side the region is not on.
        n = np.array([t[1], -t[0]]) / np.linalg.norm(t)
        return -n if even_odd_inside(fine, bezier_eval(P, 0.5) + n * 1e-9 * size) else n

    pieces = [f]
    for l in f[1]:
        m = len(l)
        for i in range(m):
            pa, ca = l[(i - 1) % m]
            v, cv = l[i]
            nxt = l[(i + 1) % m][0]
            pieces.append(("ellipse", np.eye(2) * k, np.array(v, float)))
            if join == "round":
                continue
            P1, P2 = bezier_points(pa, ca, v), bezier_points(v, cv, nxt)
            t1 = v - (P1[-2] if not np.array_equal(P1[-2], v) else P1[0])
            t2 = (P2[1] if not np.array_equal(P2[1], v) else P2[-1]) - v
            if np.linalg.norm(t1) == 0 or np.linalg.norm(t2) == 0:
                continue
            # The sides at the middles, carried to the ends (a quadratic
            # turns less than half a turn: its normal keeps its side).
            mid1 = bezier_eval(P1, 0.5) - bezier_eval(P1, 0.5 - 1e-6)
            mid2 = bezier_eval(P2, 0.5 + 1e-6) - bezier_eval(P2, 0.5)
            s1 = np.sign(outward(P1, 0.5, mid1) @ np.array([mid1[1], -mid1[0]]))
            s2 = np.sign(outward(P2, 0.5, mid2) @ np.array([mid2[1], -mid2[0]]))
            n1 = s1 * np.array([t1[1], -t1[0]]) / np.linalg.norm(t1) * side
            n2 = s2 * np.array([t2[1], -t2[0]]) / np.linalg.norm(t2) * side
            if t2 @ n1 >= 0 or 1 - n1 @ n2 <= 1e-12:
                continue  # reflex as the offset side sees it, or tangent
            pieces.append(join_piece(join, v, n1, n2, t1, t2, k))
    return ("op", "union" if d > 0 else "difference", pieces, ("bands", k))


def join_piece(join, v, n1, n2, t1, t2, k):
    """Clipper's join at corner v (edges arriving along t1 and leaving
    along t2, offset-side unit normals n1 and n2) at distance k: the disc
    (round), the kite to the offset edges' meeting point (miter), or that
    kite cut across the bisector at distance k (square, and a miter beyond
    the limit)."""
    cos = float(n1 @ n2)
    if join == "round":
        return ("ellipse", np.eye(2) * k, v.copy())
    if join == "miter" and 1 + cos >= 2e-12:
        return ("poly", [np.array([v, v + k * n1, v + (n1 + n2) * (k / (1 + cos)), v + k * n2])])
    # The cut at distance k along the bisector meets the offset edges
    # k tan(theta / 4) beyond their ends.
    theta = math.atan2(abs(n1[0] * n2[1] - n1[1] * n2[0]), cos)
    run = k * math.tan(theta / 4)
    u1, u2 = t1 / np.linalg.norm(t1), t2 / np.linalg.norm(t2)
    return ("poly", [np.array([v, v + k * n1, v + k * n1 + run * u1, v + k * n2 - run * u2, v + k * n2])])


def convex_hull_2d(pts):
    """Andrew's monotone chain: the hull's corners, counter-clockwise."""
    pts = sorted(set(map(tuple, np.asarray(pts, dtype=float).tolist())))
    if len(pts) < 3:
        return np.array(pts)
    cross = lambda o, a, b: (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def convex_poly(f):
    """The corners of a 2-D leaf that is one convex polygon, else None."""
    if f[0] != "poly" or len(f[1]) != 1:
        return None
    loop = np.asarray(f[1][0], dtype=float)
    h = convex_hull_2d(loop)
    area = lambda l: 0.5 * abs(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1]))
    if len(h) < 3 or abs(area(h) - area(loop)) > 1e-12 * area(h):
        return None
    return h


def convex_parts(f):
    """[(corners, radius)] of a union of convex polygons and circles (a
    circle its centre and radius), else None: csgrt's convex pieces."""
    if f[0] == "ellipse":
        A = f[1]
        r = float(np.linalg.norm(A[:, 0]))
        if abs(A[:, 0] @ A[:, 1]) <= 1e-12 * r * r and abs(np.linalg.norm(A[:, 1]) - r) <= 1e-12 * r:
            return [(np.asarray(f[2], dtype=float)[None, :], r)]
        return None
    if f[0] == "poly":
        h = convex_poly(f)
        return None if h is None else [(h, 0.0)]
    if f[0] == "op" and f[1] == "union" and len(f) == 3:
        parts = [convex_parts(k) for k in f[2]]
        return None if any(p is None for p in parts) else [x for p in parts for x in p]
    return None


def grown_convex(pts, r, m):
    """The convex polygon of corners pts (counter-clockwise) grown by a
    disc of radius r, as csgrt writes it: each edge pushed out by r as one
    polygon, a disc on each corner; manifold's own offset of the polygon
    in the oracle's mesh."""
    n = len(pts)
    parts = [("ellipse", np.eye(2) * r, p.copy()) for p in pts] if r > 0 else []
    if n >= 3 and r > 0:
        out = []
        for i in range(n):
            a, b = pts[i], pts[(i + 1) % n]
            e = (b - a) / np.linalg.norm(b - a)
            o = np.array([e[1], -e[0]]) * r
            out += [a + o, b + o]
        parts.append(("poly", [np.array(out)]))
    elif n == 2 and r > 0:
        e = (pts[1] - pts[0]) / np.linalg.norm(pts[1] - pts[0])
        o = np.array([e[1], -e[0]]) * r
        parts.append(("poly", [np.array([pts[0] + o, pts[1] + o, pts[1] - o, pts[0] - o])]))
    elif n >= 3:
        parts.append(("poly", [pts.copy()]))
    if not parts:
        return None
    if len(parts) == 1:
        return flat_moved(parts[0], m)
    moved = [flat_moved(k, m) for k in parts]
    if n >= 3:
        return ("op", "union", moved, ("round", r, ("poly", [pts.copy()]), m))
    return ("op", "union", moved)


def translation_2d(v):
    return np.array([[1.0, 0.0, v[0]], [0.0, 1.0, v[1]], [0.0, 0.0, 1.0]])


def sum_choices(start, pieces):
    """Every choice of one (corners, radius) from each of pieces, summed onto
    start: the hull of the corners' sums, with the radii's sum."""
    combos = [start]
    for op in pieces:
        combos = [(convex_hull_2d((a[:, None, :] + b[None, :, :]).reshape(-1, 2)), ra + rb) for a, ra in combos for b, rb in op]
    return combos


def minkowski_flat(kids, m):
    """2-D minkowski() of flat trees read in its own frame, moved by m, as
    csgrt sums them: the circles' sum (centre c, radius r) grows the rest;
    unions of convex polygons and circles sum piece by piece (the hull of
    the corners' sums, grown by the radii's); one other shape grows by r as
    offset(r) does (the same pieces; manifold's own offset in the oracle's
    mesh). Any other sum is not in the oracle."""
    circles, rest = [], []
    for k in kids:
        c = convex_parts(k) if k[0] == "ellipse" else None
        (circles if c else rest).append(c[0] if c else k)
    c = sum((x[0][0] for x in circles), np.zeros(2))
    r = sum(x[1] for x in circles)
    pieces = [convex_parts(k) for k in rest]
    whole = [k for k, p in zip(rest, pieces) if p is None]
    pieces = [p for p in pieces if p is not None]
    if len(whole) == 1 and not pieces:
        child = flat_moved(whole[0], translation_2d(c))
        if r == 0:
            return flat_moved(child, m)
        if has_section(child):
            raise ValueError("a minkowski sum with a projection is not in the oracle")
        grown = offset_pieces(child, "round", r)
        if grown is None or grown[0] != "op":
            return None if grown is None else flat_moved(grown, m)
        return ("op", grown[1], [flat_moved(k, m) for k in grown[2]], ("round", r, child, m))
    if len(whole) == 1 and r == 0 and whole[0][0] == "poly" and all(rr == 0 for op in pieces for _, rr in op):
        # A + B = (A + b) u (edges of A + B) for a convex B (b a point of B):
        # A moved by B's first corner, and each edge's hull with B; in the
        # oracle's mesh, manifold's union of A's triangles' hulls with B.
        parts = []
        for b, _ in sum_choices((np.zeros((1, 2)), 0.0), pieces):
            shifted = flat_moved(whole[0], translation_2d(b[0]))
            kids = [flat_moved(shifted, m)]
            for l in whole[0][1]:
                for i in range(len(l)):
                    h = convex_hull_2d(np.concatenate([b + l[i], b + l[(i + 1) % len(l)]]))
                    if len(h) >= 3:
                        kids.append(flat_moved(("poly", [h]), m))
            parts.append(("op", "union", kids, ("sum", b, whole[0], m)))
        return parts[0] if len(parts) == 1 else ("op", "union", parts)
    if whole:
        raise ValueError("minkowski of 2-D shapes that are not convex, other than one with circles or one polygon with convex polygons, is not in the oracle")
    if not pieces:
        return flat_moved(("ellipse", np.eye(2) * r, c), m) if r > 0 else None
    parts = [g for g in (grown_convex(p, rr, m) for p, rr in sum_choices((c[None, :], r), pieces)) if g is not None]
    if not parts:
        return None
    return parts[0] if len(parts) == 1 else ("op", "union", parts)


def has_section(f):
    return f is not None and (f[0] in ("section", "shadow") or f[0] == "op" and any(has_section(k) for k in f[2]))


def flat_stmt(s):
    """Whether a statement makes a 2-D shape."""
    return dimension(s) is True


def dimension(s):
    """OpenSCAD 2021.01's dimension of what a statement makes (its
    GeometryEvaluator::applyToChildren): True for a 2-D shape, False for a
    solid, None for nothing (a skipped statement, an empty group); a
    transform, operation, colour or resize has its first child's that has
    one."""
    if "%" in s.mods or "*" in s.mods:
        return None
    if s.name in meaning.SHAPES_2D and s.name != "import" or s.name in ("offset", "projection"):
        return True
    if s.name == "import":
        f = next((v for k, v in s.args if k in ("file", None) and isinstance(v, str)), "")
        return True if f.lower().endswith((".dxf", ".svg")) else False
    if s.name in meaning.TRANSFORMS or s.name in ("union", "intersection", "difference", "group", "render", "color", "material", "resize", "hull", "minkowski"):
        return next((d for d in map(dimension, s.children) if d is not None), None)
    if s.name in meaning.SOLIDS or s.name in meaning.EXTRUSIONS:
        return False
    return None


def operands(children):
    """The live children as OpenSCAD's render takes them: a child of the
    other dimension than the first that has one stands as None."""
    live = [c for c in children if not ("%" in c.mods or "*" in c.mods)]
    first = next((d for d in map(dimension, live) if d is not None), None)
    return [None if first is not None and dimension(c) not in (None, first) else c for c in live]


def curve_pieces(f):
    """The edges of a ("curves", loops) leaf as (a, c or None, b)."""
    return [(l[i][0], l[i][1], l[(i + 1) % len(l)][0]) for l in f[1] for i in range(len(l))]


def bezier_points(a, c, b):
    """The control polygon of an edge: [a, b], [a, c, b] or [a, c1, c2, b]."""
    if c is None:
        return np.array([a, b])
    c = np.asarray(c, float)
    return np.array([a, c, b]) if c.ndim == 1 else np.array([a, c[0], c[1], b])


def bezier_eval(P, u):
    """Points of the Bézier curve with control points P at parameters u."""
    u = np.asarray(u, float)[..., None]
    k = len(P) - 1
    return sum(math.comb(k, i) * (1 - u) ** (k - i) * u**i * P[i] for i in range(k + 1))


def bezier_turning(P, i):
    """The parameters in (0, 1) where coordinate i of the curve is
    stationary (its derivative's roots)."""
    k = len(P) - 1
    if k < 2:
        return []
    d = [k * (P[j + 1][i] - P[j][i]) for j in range(k)]
    # The derivative in the power basis: a Bézier of degree k - 1.
    if k == 2:
        den = d[0] - d[1]
        return [d[0] / den] if den != 0 and 0 < d[0] / den < 1 else []
    qa, qb, qc = d[0] - 2 * d[1] + d[2], 2 * (d[1] - d[0]), d[0]
    if qa == 0:
        return [-qc / qb] if qb != 0 and 0 < -qc / qb < 1 else []
    disc = qb * qb - 4 * qa * qc
    if disc < 0:
        return []
    r = math.sqrt(disc)
    return [u for u in ((-qb - r) / (2 * qa), (-qb + r) / (2 * qa)) if 0 < u < 1]


def curve_extent(f):
    """The exact box (lo, hi) of a curves leaf: a curve's extremes are at
    its ends or where a coordinate's derivative vanishes."""
    pts = []
    for a, c, b in curve_pieces(f):
        pts.append(a)
        if c is not None:
            P = bezier_points(a, c, b)
            for i in range(2):
                pts += [bezier_eval(P, u) for u in bezier_turning(P, i)]
    pts = np.array(pts)
    return pts.min(axis=0), pts.max(axis=0)


def clip_right(loops):
    """Each loop cut to x >= 0 (Sutherland-Hodgman)."""
    out = []
    for l in loops:
        pts = []
        for i in range(len(l)):
            a, b = l[i], l[(i + 1) % len(l)]
            if a[0] >= 0:
                pts.append(a)
            if (a[0] >= 0) != (b[0] >= 0):
                f = a[0] / (a[0] - b[0])
                pts.append(np.array([0.0, a[1] + f * (b[1] - a[1])]))
        if len(pts) >= 3:
            out.append(np.array(pts))
    return out


def flat_mirror(f):
    """The tree mirrored in x = 0."""
    if f[0] == "curves":
        fl = lambda q: None if q is None else q * [-1.0, 1.0]
        return ("curves", [[(fl(q), fl(c)) for q, c in l] for l in f[1]])
    if f[0] == "poly":
        return ("poly", [l * [-1.0, 1.0] for l in f[1]])
    if f[0] == "ellipse":
        return ("ellipse", np.diag([-1.0, 1.0]) @ f[1], f[2] * [-1.0, 1.0])
    return ("op", f[1], [flat_mirror(k) for k in f[2]])


def flat_x_range(f):
    """The x extent of a 2-D tree (union joins, intersection meets, a
    difference keeps its first operand's), as csgrt reads OpenSCAD's axis
    rule for rotate_extrude."""
    return flat_range(f, 0)


def flat_range(f, k):
    """The extent along axis k (0 = x, 1 = y), by flat_x_range's rules."""
    if f[0] == "poly":
        xs = np.concatenate([l[:, k] for l in f[1]])
        return xs.min(), xs.max()
    if f[0] == "curves":
        lo, hi = curve_extent(f)
        return lo[k], hi[k]
    if f[0] == "ellipse":
        h = math.hypot(f[1][k, 0], f[1][k, 1])
        return f[2][k] - h, f[2][k] + h
    rs = [flat_range(c, k) for c in f[2]]
    if f[1] in ("union", "xor", "hull"):
        return min(r[0] for r in rs), max(r[1] for r in rs)
    if f[1] == "intersection":
        return max(r[0] for r in rs), min(r[1] for r in rs)
    return rs[0]


def flat_empty_beyond_axis(f, right, n=41):
    """Whether a 2-D tree has no area at x > 0 (right) or x < 0, by its
    extent or, failing that, by point tests on an n x n grid of the box's
    part on that side (its inside points: none). False where a part has no
    point test."""
    lo, hi = flat_x_range(f)
    if (right and hi <= 0) or (not right and lo >= 0):
        return True
    ylo, yhi = flat_range(f, 1)
    far = hi if right else lo
    for x in np.linspace(0.0, far, n)[1:]:
        for y in np.linspace(ylo, yhi, n):
            got = flat_inside(f, np.array([x, y]))
            if got is None or got:
                return False
    return True


def flat_inside(f, p):
    """Whether p is in a 2-D tree of polygons, ellipses and their
    combinations (None for any other part)."""
    if f[0] == "poly":
        return even_odd_inside(f[1], p)
    if f[0] == "ellipse":
        q = np.linalg.solve(f[1], np.asarray(p) - f[2])
        return q @ q <= 1.0
    if f[0] != "op" or not (len(f) == 3 or plain_op(f)):
        return None
    ins = [flat_inside(k, p) for k in f[2]]
    if any(i is None for i in ins):
        return None
    if f[1] == "union":
        return any(ins)
    if f[1] == "intersection":
        return all(ins)
    if f[1] == "difference":
        return ins[0] and not any(ins[1:])
    if f[1] == "xor":
        return sum(map(bool, ins)) % 2 == 1
    return None


def hull_polygon(f):
    """A 2-D hull of polygons, circles and their combinations as a polygon
    that frames as the hull does: the hull of the points of its children's
    boundaries that can be extreme along an axis or in distance from the
    origin (corners, points where two boundaries cross, each circle's
    points along the axes and farthest from the origin), those in the
    closed region (within 1e-9 of its size). None for other children (they
    frame by their boxes)."""
    pts = []
    for kid in f[2]:
        got = edges_and_circles(kid, lambda g: g[0] == "op" and len(g) == 3 and g[1] != "xor")
        if got is None or flat_inside(kid, np.zeros(2)) is None:
            return None
        segs, circles = got
        cand = [np.asarray(a, float) for a, _ in segs]
        for c, r in circles:
            cand += [c + r * np.array(v, float) for v in ((1, 0), (0, 1), (-1, 0), (0, -1))]
            if np.any(c):
                cand.append(c + r * c / np.linalg.norm(c))
        for i, (a, b) in enumerate(segs):
            a, b = np.asarray(a, float), np.asarray(b, float)
            d = b - a
            for p0, q0 in segs[i + 1 :]:
                e = np.asarray(q0, float) - p0
                den = d[0] * e[1] - d[1] * e[0]
                if den != 0:
                    w = np.asarray(p0, float) - a
                    u, v = (w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den
                    if 0 <= u <= 1 and 0 <= v <= 1:
                        cand.append(a + u * d)
            for c, r in circles:
                A, B, C = d @ d, 2 * (a - c) @ d, (a - c) @ (a - c) - r * r
                disc = B * B - 4 * A * C
                if A > 0 and disc >= 0:
                    cand += [a + u * d for u in ((-B - math.sqrt(disc)) / (2 * A), (-B + math.sqrt(disc)) / (2 * A)) if 0 <= u <= 1]
        for i, (c1, r1) in enumerate(circles):
            for c2, r2 in circles[i + 1 :]:
                dd = c2 - c1
                l = float(np.linalg.norm(dd))
                if 0 < l <= r1 + r2 and l >= abs(r1 - r2):
                    x = (r1 * r1 - r2 * r2 + l * l) / (2 * l)
                    h = math.sqrt(max(r1 * r1 - x * x, 0.0))
                    mid, perp = c1 + dd * x / l, np.array([-dd[1], dd[0]]) / l
                    cand += [mid + h * perp, mid - h * perp]
        size = max(float(np.abs(q).max()) for q in cand) if cand else 1.0
        eps = 1e-9 * max(size, 1e-300)
        dirs = [np.array([math.cos(t), math.sin(t)]) for t in 2 * math.pi * np.arange(16) / 16]
        pts += [q for q in cand if flat_inside(kid, q) or any(flat_inside(kid, q + eps * v) for v in dirs)]
    if len(pts) < 3:
        return None
    h = convex_hull_2d(np.array(pts))
    return ("poly", [np.asarray(h, float)]) if len(h) >= 3 else None


def is_circle(A):
    """Whether A maps the unit circle to a circle (as csgrt decides)."""
    x, y = A[:, 0], A[:, 1]
    r2 = x @ x
    return abs(x @ y) <= 1e-12 * r2 and abs(y @ y - r2) <= 1e-12 * r2
