#!/usr/bin/env python3
"""csgrt against OpenSCAD's own meshes of the same scenes, ray by ray.

    python -m tools.oracle.openscad_meshes [--csgrt BIN] [--only TEXT]
    python -m tools.oracle.openscad_meshes --regenerate

Every OpenSCAD-language test scene — tests/openscad/*.csg, the
tests/scenes/*.csg without csgrt's own statements, and the certified
approximations' tests/approximated/*.csg — has OpenSCAD 2021.01's
own mesh of it in tests/openscad_meshes/NAME.off, made by `openscad -o
NAME.off SCENE` (`--regenerate` makes them again with the `openscad` on
PATH, Debian's fonts-liberation2 installed so that its text is in csgrt's
built-in font; a scene OpenSCAD makes no 3-D mesh of — a 2-D model, a statement it
does not know — is listed in tests/openscad_meshes/none.txt with
OpenSCAD's reason). Nothing there is csgrt's.

For each scene with a mesh, rays through every pixel of a WIDTH x HEIGHT
pinhole camera that looks at the mesh's box from the front-right-above are
traced by csgrt (`--trace-rays`) and cast here against OpenSCAD's
triangles (Moller-Trumbore, exact up to rounding). They must agree: hit
or miss, and the distance to the first surface within the scene's
faceting bound s / max(|n . d|, GRAZE) (n csgrt's normal, d the ray),
s the largest sagitta r (1 - cos(a)) of the scene's curved statements,
a = pi / n (a sphere's facet: the hypotenuse of pi / n and half its
ring step; a turn's sagitta added to the largest other), n OpenSCAD's
fragments for r by their $fn, $fa, $fs
(Calc::get_fragments_from_r; r the statement's own radius, or the mesh's
half-diagonal where it has none: turns, offsets, drawings, text, and
under a resize; times the largest stretch of the multmatrix blocks
around it), plus 1e-5 of
the largest coordinate (the OFF file's 6 significant digits). A ray counts as a disagreement only when the rays of
its whole 3 x 3 block of pixels disagree: edges, silhouettes and
creases, where a facet's ray may meet another surface, stay out.

A scene listed in tests/openscad_meshes/by_design.txt (class font,
openscad or open, and its reason) may disagree; listed and agreeing, it
fails. Prints a line a scene and `N passed, N failed, N in the table`;
exit status 1 on a failure.
"""

import argparse
import concurrent.futures
import glob
import math
import os
import re
import subprocess
import sys

import numpy as np

from tools import ROOT

MESHES = os.path.join(ROOT, "tests", "openscad_meshes")
WIDTH, HEIGHT = 96, 72
GRAZE = 0.2
CSGRT_STATEMENTS = re.compile(r"\b(camera|point_light|directional_light|ambient_light|material|background|torus|halfspace)\s*\(")


def scenes():
    """The OpenSCAD-language scenes: (name, path)."""
    out = [(os.path.basename(p)[:-4], p) for p in sorted(glob.glob(os.path.join(ROOT, "tests", "openscad", "*.csg")))]
    for p in sorted(glob.glob(os.path.join(ROOT, "tests", "scenes", "*.csg"))):
        if not CSGRT_STATEMENTS.search(open(p).read()):
            out.append(("scenes_" + os.path.basename(p)[:-4], p))
    # csgrt's certified approximations (no oracle of its own reads them).
    for p in sorted(glob.glob(os.path.join(ROOT, "tests", "approximated", "*.csg"))):
        out.append(("approximated_" + os.path.basename(p)[:-4], p))
    return out


def regenerate():
    os.makedirs(MESHES, exist_ok=True)
    none = []
    for name, path in scenes():
        off = os.path.join(MESHES, name + ".off")
        if os.path.exists(off):
            os.remove(off)
        try:
            p = subprocess.run(["openscad", "-o", off, path], capture_output=True, text=True, errors="replace", timeout=900)
            said = [x.strip() for x in p.stderr.splitlines() if "ERROR" in x or "not a 3D" in x or "3D object" in x]
        except subprocess.TimeoutExpired:
            said = ["over 900 s"]
        if not os.path.exists(off) or os.path.getsize(off) == 0:
            if os.path.exists(off):
                os.remove(off)
            none.append(f"{name}\t{said[0] if said else 'no mesh'}")
        print(name, "mesh" if os.path.exists(off) else "none", flush=True)
    with open(os.path.join(MESHES, "none.txt"), "w") as f:
        f.write("# Scenes OpenSCAD 2021.01 makes no 3-D mesh of (openscad -o NAME.off SCENE), and why.\n")
        f.write("".join(x + "\n" for x in none))


def read_off(path):
    """(vertices, triangles) of an OFF file, polygons fanned."""
    words = open(path).read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    vals = words[4:]
    V = np.array(vals[: 3 * nv], float).reshape(-1, 3)
    i, tris = 3 * nv, []
    for _ in range(nf):
        k = int(vals[i])
        idx = [int(x) for x in vals[i + 1 : i + 1 + k]]
        i += 1 + k
        tris += [(idx[0], idx[j], idx[j + 1]) for j in range(1, k - 1)]
    return V, np.array(tris, int).reshape(-1, 3)


def fragments(r, fn, fa, fs):
    """OpenSCAD's Calc::get_fragments_from_r."""
    if r < 0.00000095367431640625:
        return 3
    if fn > 0:
        return max(int(fn), 3)
    return int(math.ceil(max(min(360.0 / fa, r * 2 * math.pi / fs), 5)))


def sagitta(text, half_diagonal):
    """The largest sagitta of the scene's curved statements (see above),
    each radius times the largest stretch of the multmatrix blocks around
    its statement."""
    special = lambda line, k, d: float(m.group(1)) if (m := re.search(r"\$" + k + r" = ([-0-9.e]+)", line)) else d
    s, turned, stretch, resized = 0.0, 0.0, [1.0], [False]
    for line in text.splitlines():
        opened, closed = line.count("{"), line.count("}")
        m = re.match(r"\s*(%|\*|#|!)?\s*(\w+)\(", line)
        name = m.group(2) if m else ""
        if name == "multmatrix" and opened:
            rows = re.findall(r"\[([-0-9.e, ]+)\]", line)[:3]
            M = np.array([[float(x) for x in r.split(",")][:3] for r in rows])
            stretch.append(stretch[-1] * float(np.linalg.svd(M, compute_uv=False)[0]))
        elif opened:
            stretch.append(stretch[-1])
        if opened:
            resized.append(resized[-1] or name == "resize")
        for _ in range(closed):
            if len(stretch) > 1:
                stretch.pop()
                resized.pop()
        under = 1 if opened else 0
        for found in re.finditer(r"\b(circle|sphere|cylinder|rotate_extrude|offset|import|text|linear_extrude)\s*\(", line):
            name, args = found.group(1), line[found.start() :]
            if name == "linear_extrude" and not re.search(r"twist = [-0-9.]*[1-9]", args):
                continue
            if name == "import" and not re.search(r'\.(dxf|svg)"', args):
                continue
            fn, fa, fs = special(args, "fn", 0.0), special(args, "fa", 12.0), special(args, "fs", 2.0)
            radii = [float(x) for x in re.findall(r"\b(?:r|r1|r2) = ([0-9.e]+)", args)]
            radii += [float(x) / 2 for x in re.findall(r"\bd = ([0-9.e]+)", args)]
            # (a scene written by hand: the radius as the first argument)
            radii += [float(x) for x in re.findall(r"^(?:sphere|circle)\(\s*([0-9.e]+)\s*[,)]", args)]
            # Each radius with the size it has in the world: stretched by
            # the multmatrix blocks around it; the mesh's half-diagonal
            # where it has none of its own (turns, offsets, drawings,
            # text) or a resize stretches it by a factor not known here.
            k = stretch[-1 - under]
            if name in ("rotate_extrude", "import", "text", "linear_extrude") or not radii:
                sized = [(half_diagonal, half_diagonal)]
            elif resized[-1 - under]:
                sized = [(r, half_diagonal) for r in radii]
            else:
                sized = [(r, k * r) for r in radii]
            for r, world in sized:
                n = fragments(r, fn, fa, fs)
                # A sphere's facet spans a step of longitude and one of its
                # (n + 1) // 2 rings: its far point is half its diagonal away.
                if name == "sphere":
                    angle = math.hypot(math.pi / n, math.pi / (2 * ((n + 1) // 2)))
                else:
                    angle = math.pi / n
                one = world * (1 - math.cos(min(angle, math.pi / 2)))
                if name == "rotate_extrude":
                    turned = max(turned, one)
                else:
                    s = max(s, one)
    # A turn's facets stray from its profile's by the turn's own sagitta.
    return s + turned


def camera(V):
    """(eye, directions H x W x 3) of a 40-degree pinhole looking at the box
    of V from the front-right-above."""
    lo, hi = V.min(axis=0), V.max(axis=0)
    c, radius = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    back = np.array([0.55, -0.75, 0.62])
    back /= np.linalg.norm(back)
    eye = c + back * radius / math.sin(math.radians(20)) * 1.05
    w = -back
    u = np.cross(w, [0, 0, 1.0])
    u /= np.linalg.norm(u)
    v = np.cross(u, w)
    t = math.tan(math.radians(20))
    xs = (np.arange(WIDTH) + 0.5) / WIDTH * 2 - 1
    ys = 1 - (np.arange(HEIGHT) + 0.5) / HEIGHT * 2
    d = w + t * xs[None, :, None] * u * WIDTH / HEIGHT + t * ys[:, None, None] * v
    return eye, d / np.linalg.norm(d, axis=2, keepdims=True)


def cast(V, T, eye, dirs):
    """The nearest t > 0 along each ray to OpenSCAD's triangles (inf for a
    miss), tested tile by tile against the triangles whose projection
    meets the tile."""
    h, w, _ = dirs.shape
    A, B, C = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
    out = np.full((h, w), np.inf)
    # Each triangle's pixel box: its corners projected (corners behind the
    # eye put it in every tile).
    fwd = dirs[h // 2, w // 2]
    px = []
    for P in (A, B, C):
        rel = P - eye
        depth = rel @ fwd
        px.append((rel, depth))
    behind = np.any([d <= 1e-12 for _, d in px], axis=0)
    # Pixel coordinates by solving against the image basis.
    u = np.cross(fwd, [0, 0, 1.0])
    u /= np.linalg.norm(u)
    v = np.cross(u, fwd)
    t = math.tan(math.radians(20))
    cols, rows = [], []
    for rel, depth in px:
        dd = np.where(depth > 1e-12, depth, 1.0)
        cols.append(((rel @ u) / dd / (t * w / h) + 1) / 2 * w - 0.5)
        rows.append((1 - (rel @ v) / dd / t) / 2 * h - 0.5)
    c0, c1 = np.floor(np.min(cols, axis=0)) - 1, np.ceil(np.max(cols, axis=0)) + 1
    r0, r1 = np.floor(np.min(rows, axis=0)) - 1, np.ceil(np.max(rows, axis=0)) + 1
    tile = 8
    E1, E2 = B - A, C - A
    for ty in range(0, h, tile):
        for tx in range(0, w, tile):
            sel = behind | ((c1 >= tx) & (c0 < tx + tile) & (r1 >= ty) & (r0 < ty + tile))
            if not sel.any():
                continue
            D = dirs[ty : ty + tile, tx : tx + tile].reshape(-1, 3)
            a, e1, e2 = A[sel], E1[sel], E2[sel]
            p = np.cross(D[:, None, :], e2[None, :, :])
            det = np.einsum("tk,rtk->rt", e1, p)
            ok = np.abs(det) > 1e-300
            inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
            s = eye - a
            uu = np.einsum("tk,rtk->rt", s, p) * inv
            q = np.cross(s, e1)
            vv = np.einsum("rk,tk->rt", D, q) * inv
            tt = np.einsum("tk,tk->t", e2, q)[None, :] * inv
            hit = ok & (uu >= 0) & (vv >= 0) & (uu + vv <= 1) & (tt > 1e-9)
            best = np.where(hit, tt, np.inf).min(axis=1)
            hh, ww = min(tile, h - ty), min(tile, w - tx)
            out[ty : ty + hh, tx : tx + ww] = best.reshape(hh, ww)
    return out


def traced(binary, scene, eye, dirs):
    """csgrt's (t, normal) per ray (t inf for a miss), or why not."""
    e = [float(x) for x in eye]
    rays = "".join(f"{e[0]!r} {e[1]!r} {e[2]!r} {float(d[0])!r} {float(d[1])!r} {float(d[2])!r}\n" for d in dirs.reshape(-1, 3))
    p = subprocess.run([binary, scene, "--trace-rays", "-"], input=rays, capture_output=True, text=True, errors="replace")
    if p.returncode != 0:
        lines = [x for x in p.stderr.splitlines() if x.startswith("error")] or p.stderr.strip().splitlines() or ["no message"]
        return None, None, lines[0]
    ts, ns = [], []
    for line in p.stdout.splitlines():
        f = line.split()
        if f[0] == "miss":
            ts.append(np.inf)
            ns.append((0.0, 0.0, 0.0))
        else:
            ts.append(float(f[0]))
            ns.append(tuple(map(float, f[1:4])))
    return np.array(ts).reshape(dirs.shape[:2]), np.array(ns).reshape(dirs.shape), ""


def blobs(bad):
    """Pixels whose whole 3 x 3 block is bad."""
    h, w = bad.shape
    p = np.pad(bad, 1, constant_values=False)
    out = np.ones_like(bad)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            out &= p[1 + dy : 1 + dy + h, 1 + dx : 1 + dx + w]
    return out


def by_design():
    """{scene: (class, reason)} from by_design.txt."""
    table = {}
    for n, line in enumerate(open(os.path.join(MESHES, "by_design.txt")), 1):
        line = line.strip()
        if line and not line.startswith("#"):
            parts = line.split(None, 2)
            if len(parts) < 3 or parts[1] not in ("font", "openscad", "open"):
                sys.exit(f"by_design.txt:{n}: expected NAME font|openscad|open REASON")
            table[parts[0]] = (parts[1], parts[2])
    return table


def check(job):
    binary, name, path = job
    off = os.path.join(MESHES, name + ".off")
    V, T = read_off(off)
    eye, dirs = camera(V)
    mine, normals, why = traced(binary, path, eye, dirs)
    if mine is None:
        return name, False, f"csgrt refuses it: {why}"
    theirs = cast(V, T, eye, dirs)
    half = np.linalg.norm(V.max(axis=0) - V.min(axis=0)) / 2
    # OpenSCAD writes the OFF file's numbers to 6 significant digits.
    s = sagitta(open(path).read(), half) + 1e-5 * float(np.abs(V).max())
    hit_a, hit_b = np.isfinite(mine), np.isfinite(theirs)
    cos = np.abs(np.einsum("hwk,hwk->hw", normals, dirs))
    both = hit_a & hit_b
    dt = np.where(both, np.abs(np.where(both, mine, 0) - np.where(both, theirs, 0)), 0.0)
    bad = (hit_a != hit_b) | (both & (dt > s / np.maximum(cos, GRAZE)))
    found = blobs(bad)
    n = int(found.sum())
    said = f"{hit_b.sum()} of {hit_b.size} rays hit OpenSCAD's {len(T)} triangles, {hit_a.sum()} csgrt's solid; bound s = {s:.3g}"
    if n:
        y, x = np.argwhere(found)[0]
        d = dirs[y, x]
        ray = " ".join(repr(float(x)) for x in (*eye, *d))
        said += f"; {n} rays disagree, first pixel ({x}, {y}): csgrt {mine[y, x]:.6g}, OpenSCAD {theirs[y, x]:.6g} (ray {ray})"
    return name, n == 0, said


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    ap.add_argument("--only", default="", help="comma-separated texts: only scenes whose name holds one")
    ap.add_argument("--regenerate", action="store_true", help="make OpenSCAD's meshes again (needs openscad)")
    a = ap.parse_args()
    if a.regenerate:
        regenerate()
        return 0
    only = [x for x in a.only.split(",") if x]
    table = by_design()
    paths = dict(scenes())
    jobs = [(a.csgrt, n, p) for n, p in paths.items() if os.path.exists(os.path.join(MESHES, n + ".off")) and (not only or any(o in n for o in only))]
    failed = listed = 0
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as ex:
        for name, ok, said in ex.map(check, jobs):
            if name in table:
                cls, reason = table[name]
                if ok:
                    ok, said = False, f"listed as {cls} but agrees: take it out of by_design.txt"
                elif cls == "font" and "text(" not in open(paths[name]).read():
                    ok, said = False, "listed as font, but the scene has no text()"
                else:
                    listed += 1
                    print(f"table {name}: {cls}: {reason}; {said}", flush=True)
                    continue
            failed += not ok
            print(f"{'ok  ' if ok else 'FAIL'} {name}: {said}", flush=True)
    none = sum(1 for x in open(os.path.join(MESHES, "none.txt")) if x.strip() and not x.startswith("#"))
    print(f"{len(jobs) - failed - listed} passed, {failed} failed, {listed} in the table; {none} scenes OpenSCAD makes no mesh of")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
