#!/usr/bin/env python3
"""The manifold3d oracle: does csgrt see what a mesh of the same CSG tree sees?

For each scene, csgrt writes its resolved scene (--dump-scene), its hit mask
(--mask) and the first hits of a set of rays (--trace-rays). This tool rebuilds
the same solid with manifold3d from the primitives' world matrices, at several
numbers of circular segments n, and compares:

* the silhouette: the mesh is ray-cast through every pixel centre of csgrt's
  camera; each mismatched pixel is classified as on the oracle's silhouette
  edge (its 3x3 neighbourhood in the oracle mask holds both hit and miss) or
  not;
* the rays: hit/miss agreement, the distance error |t_csgrt - t_mesh| and the
  angle between the normals.

Thresholds come from the faceting bound. A mesh of n segments lies within
    delta(n) = k * R * (1 - cos(pi / n))
of the true surface, R the primitive's largest world radius and k the shape's
factor: 1 for a cylinder or cone (an inscribed regular polygon), 3 for
manifold's geodesic sphere (measured: its refined octahedron deviates
2.69 x R(1 - cos(pi/n)) at n = 64..512), and for a torus revolved from a
circle, the tube's and the sweep's bounds added. Cubes and halfspaces are
exact (delta = 0). A ray meeting a surface at angle theta to its normal sees
that offset as a distance error of at most delta / cos(theta), so

    |t_csgrt - t_mesh| <= 2 * delta(n) / cos(theta) + 1e-9 * L

(a factor 2 for the first-order estimate, L the ray's length scale), checked
where cos(theta) >= 0.25. A ray beyond that bound met a feature thinner than
the faceting (a sliver one mesh has and the other lacks): it is counted with
the hit/miss disagreements, and at the finest n every ray must be within its
bound. A silhouette pixel can only flip where the edge moved by less than a pixel,
so every mismatched pixel must lie on the oracle's silhouette edge, and the
number of mismatches must not grow as n doubles (within 2 pixels of grid
noise) and must shrink overall from n = 64 to 512, unless both are already
zero. Hit/miss disagreements of rays follow the same rule.

A halfspace is unbounded; the mesh stands it in by a box 10^6 times the
scene's size, whose far edges lie far below one pixel from the horizon.

Usage: oracle.py [--csgrt BIN] [--size WxH] [--segments 64,128,256,512]
                 [--rays N] [--out DIR] [--check] [--table FILE] SCENE...
Exit status 1 when --check finds a scene that fails.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import manifold3d as mf
import numpy as np
from PIL import Image

SPHERE_FACTOR = 3.0  # measured 2.69, rounded up
GROW_SLACK = 2  # pixels or rays of grid noise allowed when n doubles


# --------------------------------------------------------------------------
# The scene: csgrt's own outputs
# --------------------------------------------------------------------------


def run_csgrt(binary, scene, work, size, rays):
    """Dump, mask and traced rays for one scene."""
    dump, mask, image = (os.path.join(work, f) for f in ("scene.json", "mask.png", "image.png"))
    subprocess.run(
        [binary, scene, "--size", size, "--dump-scene", dump, "--mask", mask, "-o", image, "-q"],
        check=True,
    )
    with open(dump) as f:
        d = json.load(f)
    m = np.asarray(Image.open(mask).convert("L")) == 255
    ray_file = os.path.join(work, "rays.txt")
    with open(ray_file, "w") as f:
        for o, v in rays(d):
            f.write(" ".join(repr(float(x)) for x in (*o, *v)) + "\n")
    out = subprocess.run(
        [binary, scene, "--trace-rays", ray_file], check=True, capture_output=True, text=True
    ).stdout.splitlines()
    traced = []
    for line in out:
        if line == "miss":
            traced.append(None)
        else:
            t, nx, ny, nz = map(float, line.split())
            traced.append((t, np.array([nx, ny, nz])))
    with open(ray_file) as f:
        rs = [np.array(list(map(float, line.split()))) for line in f]
    return d, m, [(r[:3], r[3:] / np.linalg.norm(r[3:])) for r in rs], traced


def leaves(node):
    if node is None:
        return
    if "primitive" in node:
        yield node
    for c in node.get("children", []):
        yield from leaves(c)


def matrix(node):
    return np.array(node["matrix"], dtype=float)


def bounded_box(d):
    """World box of the bounded primitives (object boxes' corners)."""
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for p in leaves(d["root"]):
        if p["primitive"] == "halfspace":
            continue
        m = matrix(p)
        if p["primitive"] == "cylinder":
            z0 = -0.5 if p["centered"] else 0.0
            obox = [(-1, -1, z0), (1, 1, z0 + 1)]
        elif p["primitive"] == "cube" and not p["centered"]:
            obox = [(0, 0, 0), (1, 1, 1)]
        elif p["primitive"] == "torus":
            e = 1 + p["minor"]
            obox = [(-e, -e, -p["minor"]), (e, e, p["minor"])]
        else:
            obox = [(-1, -1, -1), (1, 1, 1)]
        for i in range(8):
            c = np.array([obox[(i >> k) & 1][k] for k in range(3)] + [1.0])
            w = (m @ c)[:3]
            lo, hi = np.minimum(lo, w), np.maximum(hi, w)
    if not np.all(np.isfinite(lo)):
        lo, hi = -np.ones(3), np.ones(3)
    return lo, hi


def camera(d):
    c = d["camera"]
    eye, lookat, up = (np.array(c[k], dtype=float) for k in ("eye", "lookat", "up"))
    w, h = c["width"], c["height"]
    look = lookat - eye
    du = np.cross(look, up)
    du /= np.linalg.norm(du)
    dv = np.cross(look, du)
    dv /= np.linalg.norm(dv)
    fl = w / (2 * math.tan(math.radians(c["fov"]) / 2))
    vp = look / np.linalg.norm(look) * fl - 0.5 * (w * du + h * dv)
    return eye, du, dv, vp, w, h


def make_rays(count, seed):
    """Half camera rays through random pixel centres, half random rays
    from a sphere around the solid towards points inside it."""

    def rays(d):
        rng = np.random.default_rng(seed)
        eye, du, dv, vp, w, h = camera(d)
        out = []
        for _ in range(count // 2):
            i, j = rng.integers(0, w), rng.integers(0, h)
            out.append((eye, (i + 0.5) * du + (j + 0.5) * dv + vp))
        lo, hi = bounded_box(d)
        c, r = (lo + hi) / 2, max(np.linalg.norm(hi - lo) / 2, 1e-9)
        for _ in range(count - count // 2):
            u = rng.normal(size=3)
            u /= np.linalg.norm(u)
            target = c + rng.uniform(-0.5, 0.5, size=3) * (hi - lo)
            o = c + 2 * r * u
            out.append((o, target - o))
        return out

    return rays


# --------------------------------------------------------------------------
# The mesh
# --------------------------------------------------------------------------


def sigma_max(m):
    return float(np.linalg.svd(m[:3, :3], compute_uv=False)[0])


def facet_bound(p, n):
    """How far the n-segment mesh of primitive p may lie from its surface."""
    kind, s = p["primitive"], sigma_max(matrix(p))
    b = 1 - math.cos(math.pi / n)
    if kind == "sphere":
        return SPHERE_FACTOR * s * b
    if kind == "cylinder":
        return s * max(p["r0"], p["r1"]) * b
    if kind == "torus":
        return s * ((1 + p["minor"]) * b + p["minor"] * b)
    return 0.0


def mesh(node, n, big):
    if "primitive" in node:
        kind = node["primitive"]
        if kind == "sphere":
            m = mf.Manifold.sphere(1.0, n)
        elif kind == "cube":
            c = node["centered"]
            m = mf.Manifold.cube([2.0, 2.0, 2.0], True) if c else mf.Manifold.cube([1.0, 1.0, 1.0])
        elif kind == "cylinder":
            m = mf.Manifold.cylinder(1.0, node["r0"], node["r1"], n, node["centered"])
        elif kind == "torus":
            m = mf.CrossSection.circle(node["minor"], n).translate([1.0, 0.0]).revolve(n)
        elif kind == "halfspace":
            m = mf.Manifold.cube([2 * big, 2 * big, big], True).translate([0.0, 0.0, -big / 2])
        else:
            raise ValueError(f"unknown primitive {kind}")
        return m.transform(matrix(node)[:3, :].tolist())
    kids = [mesh(c, n, big) for c in node["children"]]
    op = node["op"]
    if op == "union":
        return mf.Manifold.batch_boolean(kids, mf.OpType.Add)
    if op == "intersection":
        return mf.Manifold.batch_boolean(kids, mf.OpType.Intersect)
    rest = mf.Manifold.batch_boolean(kids[1:], mf.OpType.Add) if len(kids) > 2 else kids[1]
    return kids[0] - rest


class Caster:
    """First hits on the mesh, fast.

    manifold's ray_cast looks up candidate triangles by the box of the ray
    segment, so a long diagonal segment tests nearly every triangle. The
    ray is therefore clipped to the box of the bounded solids and cast in
    PIECES short segments; beyond that box only top-level halfspaces can be
    hit, and they are cast against separately (12 triangles each), before
    and after the box.
    """

    PIECES = 8

    def __init__(self, d, n):
        lo, hi = bounded_box(d)
        size = float(np.linalg.norm(hi - lo))
        self.big = 1e6 * max(size, 1.0)
        margin = 1e-6 * max(size, 1.0)
        self.lo, self.hi = lo - margin, hi + margin
        root = d["root"]
        self.solid = mesh(root, n, self.big) if root else mf.Manifold()
        tops = root.get("children", [root]) if root and root.get("op") == "union" else [root]
        halves = [c for c in tops if c and c.get("primitive") == "halfspace"]
        nested = [p for p in leaves(root) if p["primitive"] == "halfspace" and p not in halves]
        if nested:
            raise ValueError("a halfspace below the top-level union is not supported by the oracle")
        self.outside = (
            mf.Manifold.batch_boolean([mesh(h, n, self.big) for h in halves], mf.OpType.Add)
            if halves
            else None
        )

    @staticmethod
    def _seg(solid, o, v, a, b):
        hits = solid.ray_cast((o + a * v).tolist(), (o + b * v).tolist())
        if not hits:
            return None
        return a + hits[0].distance * (b - a), np.array(hits[0].normal, dtype=float)

    def cast(self, o, v):
        """(t, normal) of the first hit with t > 0 along unit v, or None."""
        with np.errstate(divide="ignore", invalid="ignore"):
            t0 = (self.lo - o) / v
            t1 = (self.hi - o) / v
        near = np.nanmax(np.where(np.isnan(t0), -np.inf, np.minimum(t0, t1)))
        far = np.nanmin(np.where(np.isnan(t1), np.inf, np.maximum(t0, t1)))
        near = max(near, 0.0)
        inside = near <= far and np.isfinite(far)
        # In order along the ray: the halfspaces before the box, the solid
        # in it, the halfspaces after it.
        if self.outside is not None and inside and near > 0:
            h = self._seg(self.outside, o, v, 0.0, near)
            if h:
                return h
        if inside:
            edges = np.linspace(near, far, self.PIECES + 1)
            for a, b in zip(edges, edges[1:]):
                h = self._seg(self.solid, o, v, a, b)
                if h:
                    return h
        if self.outside is None:
            return None
        h = self._seg(self.outside, o, v, far if inside else 0.0, 4 * self.big)
        # The stand-in box's far faces are not surfaces of the halfspace.
        if h and np.abs(o + h[0] * v).max() > self.big / 4:
            return None
        return h


# --------------------------------------------------------------------------
# Comparison
# --------------------------------------------------------------------------


def edge_pixels(mask):
    """Pixels whose 3x3 neighbourhood holds both hit and miss."""
    p = np.pad(mask, 1, mode="edge")
    h, w = mask.shape
    lo = np.ones_like(mask, dtype=bool)
    hi = np.zeros_like(mask, dtype=bool)
    for dy in range(3):
        for dx in range(3):
            s = p[dy : dy + h, dx : dx + w]
            lo &= s
            hi |= s
    return hi & ~lo


def compare(name, d, cmask, rays, traced, n, out_dir):
    prims = list(leaves(d["root"]))
    delta = max([facet_bound(p, n) for p in prims] + [0.0])
    caster = Caster(d, n)
    eye, du, dv, vp, w, h = camera(d)
    omask = np.zeros((h, w), dtype=bool)
    for j in range(h):
        for i in range(w):
            v = (i + 0.5) * du + (j + 0.5) * dv + vp
            omask[j, i] = caster.cast(eye, v / np.linalg.norm(v)) is not None
    mism = omask != cmask
    edge = edge_pixels(omask)
    off_edge = int(np.sum(mism & ~edge))
    # Rays. A ray beyond its bound met a feature thinner than the faceting
    # (a sliver one mesh has and the other lacks, or an edge within the
    # bound of the hit): it counts with the hit/miss disagreements, which
    # must vanish as n grows.
    disagree, worst, worst_ray, worst_abs, worst_angle, checked = 0, 0.0, None, 0.0, 0.0, 0
    for (o, v), c in zip(rays, traced):
        m = caster.cast(o, v)
        if (c is None) != (m is None):
            disagree += 1
            continue
        if c is None:
            continue
        (tc, nc), (tm, nm) = c, m
        cos = abs(float(np.dot(v, nc)))
        if cos < 0.25:
            continue
        err = abs(tc - tm)
        scale = float(np.abs(o).max() + tc)
        bound = 2 * delta / cos + 1e-9 * scale
        checked += 1
        ratio = err / bound
        if ratio > 1:
            disagree += 1
        worst_abs = max(worst_abs, err)
        angle = math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(nc, nm))))))
        worst_angle = max(worst_angle, angle)
        if ratio >= worst:
            worst, worst_ray = ratio, (o, v, tc, tm, bound)
    if out_dir and (off_edge or disagree or np.sum(mism)):
        diff = np.zeros((h, w, 3), dtype=np.uint8) + 255
        diff[cmask & omask] = (200, 200, 200)
        diff[omask & ~cmask] = (220, 30, 30)  # oracle only: red
        diff[cmask & ~omask] = (30, 60, 220)  # csgrt only: blue
        Image.fromarray(diff).save(os.path.join(out_dir, f"{name}-n{n}-diff.png"))
    return {
        "n": n,
        "delta": delta,
        "mismatch": int(np.sum(mism)),
        "off_edge": off_edge,
        "edge": int(np.sum(edge)),
        "rays": len(rays),
        "checked": checked,
        "disagree": disagree,
        "worst_ratio": worst,
        "worst_abs": worst_abs,
        "worst_ray": worst_ray,
        "worst_angle": worst_angle,
    }


def verdict(rows):
    """Problems with one scene's rows (coarsest n first), in words."""
    bad = []
    for r in rows:
        if r["off_edge"]:
            bad.append(f"n={r['n']}: {r['off_edge']} mismatched pixels off the silhouette edge")
    r = rows[-1]
    if r["worst_ratio"] > 1:
        o, v, tc, tm, b = r["worst_ray"]
        bad.append(
            f"n={r['n']}: distance error {abs(tc - tm):.3g} exceeds its bound {b:.3g} "
            f"on the ray {' '.join(f'{x:.17g}' for x in (*o, *v))} "
            f"(csgrt t = {tc:.17g}, mesh t = {tm:.17g})"
        )
    for key in ("mismatch", "disagree"):
        seq = [r[key] for r in rows]
        for a, b, r in zip(seq, seq[1:], rows[1:]):
            if b > a + GROW_SLACK:
                bad.append(f"{key} grew from {a} to {b} at n={r['n']}")
        if seq[0] > 0 and seq[-1] >= seq[0] and seq[-1] > GROW_SLACK:
            bad.append(f"{key} did not shrink: {seq}")
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--csgrt", default="target/release/csgrt")
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--segments", default="64,128,256,512")
    ap.add_argument("--rays", type=int, default=400)
    ap.add_argument("--out", default=None, help="folder for diff pictures")
    ap.add_argument("--check", action="store_true", help="exit 1 if a scene fails")
    ap.add_argument("--table", default=None, help="write the table (Markdown) here")
    a = ap.parse_args()
    segs = [int(s) for s in a.segments.split(",")]
    if a.out:
        os.makedirs(a.out, exist_ok=True)
    lines = [
        "| scene | n | delta | mismatched px (off edge) | rays checked | hit/miss or beyond bound | worst err/bound | worst abs err | worst normal angle |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    failed = []
    for k, scene in enumerate(a.scenes):
        name = os.path.splitext(os.path.basename(scene))[0]
        with tempfile.TemporaryDirectory() as work:
            d, cmask, rays, traced = run_csgrt(a.csgrt, scene, work, a.size, make_rays(a.rays, 1000 + k))
        rows = [compare(name, d, cmask, rays, traced, n, a.out) for n in segs]
        for r in rows:
            lines.append(
                f"| {name} | {r['n']} | {r['delta']:.3g} | {r['mismatch']} ({r['off_edge']}) | "
                f"{r['checked']}/{r['rays']} | {r['disagree']} | {r['worst_ratio']:.3g} | {r['worst_abs']:.3g} | "
                f"{r['worst_angle']:.3g}° |"
            )
            print(lines[-1], flush=True)
        bad = verdict(rows)
        if bad:
            failed.append(name)
            for b in bad:
                print(f"FAIL {name}: {b}", file=sys.stderr)
    if a.table:
        with open(a.table, "w") as f:
            f.write("\n".join(lines) + "\n")
    print(f"{len(a.scenes) - len(failed)} passed, {len(failed)} failed")
    if a.check and failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
