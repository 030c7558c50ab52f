#!/usr/bin/env python3
"""Random offsets of random 2-D combinations of circles and squares (or,
with --kind sum, their Minkowski sums with a circle or a turned rectangle;
with --kind hull, hulls of circles and squares; with --kind flat, offsets
of combinations with ellipses and hulls of ellipses, and of thin triangles
that meet at their tips — what csgrt flattens to straight polygons, or
joins by wedge; with --kind sum2, Minkowski sums of two such combinations,
neither convex), each
rendered by csgrt and by OpenSCAD itself: csgrt's prism of the result
(linear_extrude(1), traced by vertical rays on a 61 x 61 grid) against the
top faces of OpenSCAD's own mesh (`openscad -o m.off`, $fn = 256), point by
point, points within 2e-3 of OpenSCAD's outline left out (its facets and
Clipper's miters on them). A check of `offset` against the reference
implementation itself, run in CI (it needs the openscad binary and
takes about 4 s a scene).

Usage: offset_vs_openscad.py FIRST_SEED COUNT [--kind offset|sum|hull|flat|sum2] [--dir DIR] [--csgrt BIN]
Prints one line a scene and `bad N`; exit status 1 if any scene disagrees.
"""
import sys, os, subprocess, random, math, tempfile, multiprocessing, numpy as np
import manifold3d as mf
from tools.oracle import scene
from tools import ROOT
BIN = os.path.join(ROOT, "target/release/csgrt")
def shape(rng, depth=0):
    k = rng.random()
    if depth < 2 and k < 0.35:
        op = rng.choice(['union', 'difference', 'intersection'])
        kids = [shape(rng, depth+1) for _ in range(rng.randint(2, 3))]
        return f"{op}() {{ {' '.join(kids)} }}"
    if k < 0.65:
        return f"translate([{rng.uniform(-3,3):.3f}, {rng.uniform(-3,3):.3f}]) circle(r = {rng.uniform(0.5,3):.3f});"
    return f"translate([{rng.uniform(-3,3):.3f}, {rng.uniform(-3,3):.3f}]) rotate({rng.uniform(0,90):.2f}) square([{rng.uniform(0.5,4):.3f}, {rng.uniform(0.5,4):.3f}], center = true);"
def offs(rng):
    j = rng.choice(['r', 'r', 'delta', 'chamfer'])
    d = rng.choice([-1, 1]) * rng.uniform(0.1, 1.5)
    if j == 'r': return f"offset(r = {d:.3f})"
    if j == 'delta': return f"offset(delta = {d:.3f})"
    return f"offset(delta = {d:.3f}, chamfer = true)"
def piece(rng):
    """A circle or a turned rectangle, somewhere."""
    if rng.random() < 0.5:
        return f"translate([{rng.uniform(-3,3):.3f}, {rng.uniform(-3,3):.3f}]) circle(r = {rng.uniform(0.3,2):.3f});"
    return f"translate([{rng.uniform(-3,3):.3f}, {rng.uniform(-3,3):.3f}]) rotate({rng.uniform(0,90):.2f}) square([{rng.uniform(0.3,3):.3f}, {rng.uniform(0.3,3):.3f}], center = true);"
def summed(rng):
    """A Minkowski sum csgrt makes exact: any shape with a circle (its
    offset), or a union of circles and rectangles with a turned rectangle."""
    if rng.random() < 0.5:
        return f"minkowski() {{ union() {{ {shape(rng)} {shape(rng)} }} circle(r = {rng.uniform(0.1,1.5):.3f}); }}"
    parts = " ".join(piece(rng) for _ in range(rng.randint(1, 3)))
    return f"minkowski() {{ union() {{ {parts} }} rotate({rng.uniform(0,90):.2f}) square([{rng.uniform(0.2,2):.3f}, {rng.uniform(0.2,2):.3f}], center = true); }}"
def oval(rng):
    """An ellipse, turned, somewhere."""
    return (f"translate([{rng.uniform(-3,3):.3f}, {rng.uniform(-3,3):.3f}]) rotate({rng.uniform(0,180):.2f}) "
            f"scale([{rng.uniform(0.4,2.5):.3f}, {rng.uniform(0.4,2.5):.3f}]) circle(r = {rng.uniform(0.5,2):.3f});")
def curvy(rng, depth=0):
    """A combination of circles, squares, ellipses and hulls of ellipses."""
    k = rng.random()
    if depth < 2 and k < 0.4:
        op = rng.choice(['union', 'difference', 'intersection'])
        kids = [curvy(rng, depth+1) for _ in range(rng.randint(2, 3))]
        return f"{op}() {{ {' '.join(kids)} }}"
    if k < 0.6:
        return oval(rng)
    if k < 0.75:
        return f"hull() {{ {oval(rng)} {oval(rng)} }}"
    return shape(rng, 2)
def tips(rng):
    """Thin triangles whose tips meet at one point, their union cut by a
    far square (so that the offset takes its outline as one); or holes of
    that kind in a square."""
    n = rng.randint(2, 3)
    base = rng.uniform(0, 360)
    tri = []
    for i in range(n):
        a = math.radians(base + i * 360 / n + rng.uniform(-20, 20))
        w = math.radians(rng.uniform(8, 25))
        L = rng.uniform(4, 8)
        p = [(0, 0), (L * math.cos(a - w), L * math.sin(a - w)), (L * math.cos(a + w), L * math.sin(a + w))]
        tri.append("polygon([" + ", ".join(f"[{x:.4f}, {y:.4f}]" for x, y in p) + "]);")
    if rng.random() < 0.5:
        return f"difference() {{ union() {{ {' '.join(tri)} }} translate([8.5, 8.5]) square(0.1); }}"
    return f"difference() {{ square(16, center = true); {' '.join(tri)} }}"
def hulled(rng):
    return "hull() { " + " ".join(piece(rng) for _ in range(rng.randint(2, 4))) + " }"
KIND = sys.argv[sys.argv.index("--kind") + 1] if "--kind" in sys.argv else "offset"
seed0 = int(sys.argv[1]); N = int(sys.argv[2])
if "--csgrt" in sys.argv:
    BIN = sys.argv[sys.argv.index("--csgrt") + 1]
ROOT_DIR = sys.argv[sys.argv.index("--dir") + 1] if "--dir" in sys.argv else tempfile.mkdtemp(prefix="offsets-")
def check(seed):
    """(whether csgrt and OpenSCAD disagree on scene `seed`, its line)."""
    rng = random.Random(seed)
    if KIND == "offset":
        o = offs(rng)
        if rng.random() < 0.3: o = o + " " + offs(rng)
        body = f"{o} union() {{ {shape(rng)} {shape(rng)} }}"
    elif KIND == "flat":
        if rng.random() < 0.4:
            # Sharp corners: where the wedges matter.
            d = rng.choice([-1, 1]) * rng.uniform(0.1, 1.0)
            chamfer = ", chamfer = true" if rng.random() < 0.3 else ""
            body = f"offset(delta = {d:.3f}{chamfer}) {tips(rng)}"
        else:
            body = f"{offs(rng)} {curvy(rng)}"
    elif KIND == "sum2":
        extra = f" circle(r = {rng.uniform(0.1,0.8):.3f});" if rng.random() < 0.3 else ""
        body = f"minkowski() {{ {curvy(rng)} {shape(rng)}{extra} }}"
    else:
        body = summed(rng) if KIND == "sum" else hulled(rng)
    scad = f"$fn = 256;\nlinear_extrude(1) {body}\n"
    d = os.path.join(ROOT_DIR, f"s{seed}"); os.makedirs(d, exist_ok=True)
    open(f"{d}/m.scad", "w").write(scad)
    subprocess.run(["openscad", "-o", f"{d}/m.csg", f"{d}/m.scad"], capture_output=True)
    subprocess.run(["openscad", "-o", f"{d}/m.off", f"{d}/m.scad"], capture_output=True)
    # openscad's mesh: its top face z=1 polygons -> membership by a vertical ray through its mesh
    pts = np.array([[x, y] for x in np.linspace(-9, 9, 61) for y in np.linspace(-9, 9, 61)])
    rays = "\n".join(f"{x} {y} 5 0 0 -1" for x, y in pts) + "\n"
    r = subprocess.run([BIN, f"{d}/m.csg", "--trace-rays", "-"], input=rays, capture_output=True, text=True)
    if r.returncode != 0:
        return True, f"{seed} REFUSED by csgrt: {(r.stderr.strip().splitlines() or [''])[0][:150]}"
    got = [ln.split()[0] != "miss" for ln in r.stdout.strip().splitlines()]
    # OpenSCAD's own mesh, read: membership by the 2-D polygons of its top faces via manifold
    try:
        txt = open(f"{d}/m.off").read().split()
    except FileNotFoundError:
        # OpenSCAD writes no mesh for an empty result: csgrt must draw nothing.
        if any(got):
            return True, f"{seed} MISMATCH: OpenSCAD's result is empty, csgrt hits {sum(got)} rays"
        return False, f"{seed} ok (empty)"
    nv, nf = int(txt[1]), int(txt[2]); vals = txt[4:]
    V = np.array(vals[:3*nv], float).reshape(-1, 3)
    i = 3*nv; tris = []
    for _ in range(nf):
        k = int(vals[i]); idx = [int(v) for v in vals[i+1:i+1+k]]; i += 1+k
        for j in range(1, k-1): tris.append((idx[0], idx[j], idx[j+1]))
    top = [t for t in tris if all(abs(V[q, 2] - 1) < 1e-9 for q in t)]
    polys = [V[list(t), :2] for t in top]
    area = lambda p: (p[1, 0] - p[0, 0]) * (p[2, 1] - p[0, 1]) - (p[1, 1] - p[0, 1]) * (p[2, 0] - p[0, 0])
    cs = mf.CrossSection.batch_boolean([mf.CrossSection([p.tolist()], mf.FillRule.NonZero) for p in polys if abs(area(p)) > 1e-12], mf.OpType.Add) if polys else mf.CrossSection()
    loops = [np.asarray(l) for l in cs.to_polygons()]
    def dist_edge(p):
        m = 1e9
        for l in loops:
            a = l; b = np.roll(l, -1, axis=0); e = b - a
            u = np.clip(((p - a) * e).sum(1) / np.maximum((e*e).sum(1), 1e-300), 0, 1)
            m = min(m, np.min(np.linalg.norm(p - a - u[:, None]*e, axis=1)))
        return m
    mism = 0
    for p, g in zip(pts, got):
        want = scene.even_odd_inside(loops, p) if loops else False
        if want != g and dist_edge(p) > 2e-3:
            mism += 1
    if mism:
        return True, f"{seed} MISMATCH {mism} {scad.strip().replace(chr(10), ' ')[:300]}"
    return False, f"{seed} ok {sum(got)}"


# The scenes two (or as many as there are cores) at once — OpenSCAD's
# render is single-threaded — their lines printed in seed order.
bad = 0
with multiprocessing.get_context("fork").Pool(os.cpu_count() or 1) as pool:
    for failed, line in pool.imap(check, range(seed0, seed0 + N)):
        bad += failed
        print(line, flush=True)
print(f"{N - bad} passed, {bad} failed")
sys.exit(1 if bad else 0)
