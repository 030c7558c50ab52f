"""Casting rays on the oracle's own meshes with IEEE-exact slab tests."""

import math

import manifold3d as mf
import numpy as np

from tools.oracle import scene as reader
from . import mesh

__all__ = ['Caster', 'ieee_div', 'slab_range']


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
            m = mesh.leaf_mesh(node, n, self.big)
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
