"""The verdict: csgrt's image, mask and traced rays against the oracle's side,
off the edges and within the bounds, and the same-outputs check of two builds."""

import math
import os
import re
import subprocess
import tempfile

import numpy as np
from PIL import Image

from tools.oracle import scene as reader
from . import bounds
from . import cast
from . import mesh
from . import ray_sets

__all__ = ['CAP', 'SIDES', 'Side', 'check_scene', 'colour_check', 'compare', 'finest', 'framing_problems', 'judge', 'mixed', 'off_surface', 'same_outputs', 'towards', 'verdict']


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
    delta = bounds.facet_distance(leaf, n) if leaf else 0.0
    cos = abs(float(v @ nc))
    big = bounds.largest_radius(leaf) if leaf else 0.0
    scale = float(np.abs(o).max() + tc)
    dbound = min(2 * delta / cos if cos > 0 else math.inf, 2 * math.sqrt(2 * big * delta)) + 1e-9 * scale
    err = abs(tc - tm)
    angle = math.acos(max(-1.0, min(1.0, float(nc @ nm))))
    abound = bounds.FP_ANGLE
    if leaf:
        smax, smin = mesh.svd(leaf)
        kappa = smax / smin
        rho = bounds.curvature_radius(leaf, o + tm * v)
        abound += bounds.facet_angle(leaf, n) + kappa * (err + delta) / (smin * rho)
    return err <= dbound and angle <= abound, err, dbound, angle, abound


class Side:
    """What the oracle sees of one scene at n segments, csgrt aside: the
    mesh's first hit through every pixel centre and along every random
    ray, the hit and surface maps, and the edge pixels."""

    def __init__(self, sc, n, w, h, pix_rays, rays):
        self.n = n
        self.caster = cast.Caster(sc, n)
        self.hit = np.zeros((h, w), dtype=bool)
        surf = np.full((h, w), -1, dtype=np.int64)
        self.pixels = []
        for k, (o, v) in enumerate(pix_rays):
            j, i = divmod(k, w)
            m = self.caster.cast(o, v)
            self.pixels.append(m)
            if m is not None:
                self.hit[j, i] = True
                if m[2]:
                    slack = bounds.facet_distance(m[2], n)
                    surf[j, i] = m[2].id * 1_000_000 + bounds.face_class(m[2], o + m[0] * v, slack)
                else:
                    surf[j, i] = -2
        self.edge = mixed(surf)
        self.rays = [self.caster.cast(o, v) for o, v in rays]


def compare(name, sc, side, w, h, cmask, img, pix_rays, pix_traced, rays, traced, out_dir, lights):
    """One n's row; lights (the picture's, or None) asks for the colour
    check too."""
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
    if lights is not None:
        colour_check(sc, lights, side.caster, w, h, img, pix_rays, pix_traced, side.pixels, edge, n, row)
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


def colour_check(sc, all_lights, caster, w, h, img, pix_rays, pix_traced, mesh, edge, n, row):
    """Shade every opaque, non-reflective pixel off the edges with
    all_lights (the scene's as csgrt's picture has them); first pass the
    shadow maps of the lights that cast shadows (to find ambiguous
    shadows), then the colours: linear sums of the decoded colours,
    encoded as sRGB."""
    transparent = any(x.material["kt"] > 0 for x in sc.leaves)
    lights = [k for k, (kind, _, _, shadows) in enumerate(all_lights) if kind != "ambient" and shadows]
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
        delta = bounds.facet_distance(leaf, n)
        scale = float(np.abs(o).max() + tc)
        info[k] = (p, nc, leaf, delta, scale)
        for li, L in enumerate(lights):
            kind, _, x, _ = all_lights[L]
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
        colour = reader.srgb_decode(mat["color"])
        col = np.zeros(3)
        options = [np.zeros(3)]
        for li_all, (kind, il, x, shadows) in enumerate(all_lights):
            if kind == "ambient":
                col += mat["ka"] * il * colour
                continue
            # The light's shadow map, when it casts shadows.
            li = lights.index(li_all) if shadows else None
            ldir, dist = towards(kind, x, p)
            ndl = float(ns @ ldir)
            if ndl <= 0 or (mat["kd"] <= 0 and mat["ks"] <= 0):
                continue
            term = mat["kd"] * ndl * colour * il
            if mat["ks"] > 0:
                r = 2 * ndl * ns - ldir
                vr = float(-v @ r)
                if vr > 0:
                    term = term + mat["ks"] * vr ** mat["ns"] * il
            if not shadows:
                pass_ = 1.0
            elif transparent:
                pass_ = 1.0
                for t, hn, hl in caster.cast_all(off_surface(p, nc, ldir, delta, scale), ldir, dist):
                    if hn @ ldir < 0:
                        pass_ *= hl.material["kt"] if hl else 0.0
            else:
                pass_ = 0.0 if shadow[li, j, i] else 1.0
            choices = {pass_}
            if li is not None and (shadow_edge[li, j, i] or ndl < 0.02):
                choices |= {0.0, 1.0}
            options = [o + q * term for o in options for q in sorted(choices)]
        want = [np.floor(reader.srgb_encode(col + o) * 255 + 0.5) for o in options]
        got = img[j, i]
        row["colour_checked"] += 1
        if min(np.abs(got - x).max() for x in want) > bounds.COLOUR_TOLERANCE:
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
            if b > a + bounds.GROW_SLACK:
                bad.append(f"{key} grew from {a} to {b} at n={r['n']}")
        if seq[0] > 0 and seq[-1] >= seq[0] and seq[-1] > bounds.GROW_SLACK:
            bad.append(f"{key} did not shrink: {seq}")
    return bad


SIDES = {}  # (path, w, h, rays, n) -> Side: the oracle's side, once a process


CAP = re.compile(r"^// oracle: at most (\d+) segments", re.M)


def finest(path, segs):
    """The numbers of segments a scene is checked at: all of `segs`, but
    where the scene's .scad beside it says `// oracle: at most N segments`
    (manifold3d's sum of a sphere and a cylinder hulls every pair of their
    vertices: at 512 segments 130 million points), those up to N."""
    scad = os.path.splitext(path)[0] + ".scad"
    if os.path.exists(scad):
        with open(scad, encoding="utf-8") as f:
            m = CAP.search(f.read())
        if m:
            return [n for n in segs if n <= int(m.group(1))] or segs[:1]
    return segs


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
    rays = ray_sets.random_rays(sc, nrays, bounds.seed_of(name))
    with tempfile.TemporaryDirectory() as work:
        try:
            cmask, img, framed = ray_sets.render_csgrt(cmd, path, work, w, h, env)
            # The pixels of csgrt's own framing, whose box is checked below.
            view = sc.view(w, h, framed)
            pix_rays = ray_sets.camera_rays(view, w, h)
            lights = sc.lights_seen_by(view)
            traced = ray_sets.trace_csgrt(cmd, path, work, pix_rays + rays, env)
        except (subprocess.CalledProcessError, RuntimeError, ValueError, KeyError) as e:
            return [], [f"csgrt failed: {e}"]
    pix_traced, traced = traced[: len(pix_rays)], traced[len(pix_rays) :]
    rows = []
    segs = finest(path, segs)
    for n in segs:
        key = (os.path.abspath(path), w, h, nrays, n, None if framed is None else repr(framed))
        if key not in SIDES:
            SIDES[key] = Side(sc, n, w, h, pix_rays, rays)
        side = SIDES[key]
        rows.append(
            compare(name, sc, side, w, h, cmask, img, pix_rays, pix_traced, rays, traced, out_dir, lights if n == segs[-1] else None)
        )
        if first_fault and rows[-1]["off_edge"]:
            break
    framing = framing_problems(sc, framed, side)
    if first_fault and framing:
        return rows, framing
    return rows, framing + verdict(rows)


def framing_problems(sc, framed, side):
    """What is wrong with the box csgrt's default camera framed (none when
    the file gives a camera): it must be the box of the result itself.
    With a halfspace at the top level, the union of the bounded leaves'
    exact boxes. Otherwise each side within the faceting distance of the
    side of the oracle's own mesh of the result at side.n (the largest of
    its leaves': the mesh stands off the exact solid by no more, and so
    does its box), less on the inside by up to 2/64 of the box's extent
    along that axis: csgrt finds a side no exact far point shows with
    rays through a 64×64 grid over the box grown by one step
    (src/csg/extent.rs), which meets the surface within a step of its far
    point where no feature is thinner than a step."""
    if framed is None:
        return []
    lo, hi = framed
    size = float(np.linalg.norm(hi - lo)) if np.all(np.isfinite(hi - lo)) else 1.0
    tiny = 1e-9 * max(size, float(np.abs(np.concatenate([lo, hi])).max(initial=0.0)), 1.0)
    if side.caster.outside is not None:
        want_lo, want_hi = reader.bounded_box(sc)
        ok = np.allclose(lo, want_lo, rtol=0, atol=tiny) and np.allclose(hi, want_hi, rtol=0, atol=tiny)
        return [] if ok else [f"the default camera framed {lo}..{hi}, the bounded leaves' box is {want_lo}..{want_hi}"]
    if side.caster.solid.is_empty():
        return [] if np.any(lo > hi) else [f"the default camera framed {lo}..{hi}, the result is empty"]
    b = side.caster.solid.bounding_box()
    mlo, mhi = np.array(b[:3], dtype=float), np.array(b[3:], dtype=float)
    fd = max((bounds.facet_distance(x, side.n) for x in sc.leaves), default=0.0)
    inside = 2.0 * (hi - lo) / 64
    bad = (
        np.any(lo < mlo - fd - tiny)
        or np.any(lo > mlo + fd + inside + tiny)
        or np.any(hi > mhi + fd + tiny)
        or np.any(hi < mhi - fd - inside - tiny)
    )
    if bad:
        return [f"the default camera framed {lo}..{hi}, the result's mesh box at n = {side.n} is {mlo}..{mhi} (within {fd:.3g}, less {inside} inside)"]
    return []


def same_outputs(path, cmd, other, w, h, nrays, env=None):
    """Problems (none: the same) where csgrt's command `cmd` (under env)
    answers differently from `other` on everything check_scene reads of
    it — the mask, the image, the pixel-centre and random rays — so that
    the oracle's verdict on one is its verdict on the other, without
    meshing the scene again."""
    name = os.path.splitext(os.path.basename(path))[0]
    sc = reader.read(path)
    outs = []
    for c, e in ((cmd, env), (other, None)):
        with tempfile.TemporaryDirectory() as work:
            cmask, img, framed = ray_sets.render_csgrt(c, path, work, w, h, e)
            rays = ray_sets.camera_rays(sc.view(w, h, framed), w, h) + ray_sets.random_rays(sc, nrays, bounds.seed_of(name))
            traced = ray_sets.trace_csgrt(c, path, work, rays, e)
        outs.append((np.asarray(cmask), np.asarray(img), traced, framed))
    (m0, i0, t0, f0), (m1, i1, t1, f1) = outs
    bad = []
    if repr(f0) != repr(f1):
        bad.append("the framed boxes differ")
    if not np.array_equal(m0, m1):
        bad.append("the masks differ")
    if not np.array_equal(i0, i1):
        bad.append("the images differ")
    if repr(t0) != repr(t1):
        bad.append("the traced rays differ")
    return bad
