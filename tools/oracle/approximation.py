#!/usr/bin/env python3
"""csgrt's certified approximation against the exact solid, at three zooms.

A hull, a Minkowski sum or a shadow of an intersection or a difference has
no exact form in csgrt: it is cut into convex polytopes within 1/8192 of
the approximated node's size (src/scene/resolve/approximate.rs), which is
half a pixel where that node spans 4096 pixels. Each case here is a scene
whose exact solid has a closed form, and a signed distance written out in
this file:

* hull_ball_box: the hull of a ball (r 10) cut by a box (16): the cut ball
  itself, convex; its distance max(|p| - 10, |p|_inf - 8), exact inside it
  (where an inscribed approximation's surface lies) — the node is 16 wide;
* minkowski_plate: a 30 x 20 x 4 plate with a 6 x 6 hole, plus a ball of
  radius 1.5: the points within 1.5 of the plate, the plate being the union
  of four boxes, so the distance is the least of four box distances less
  1.5, exact — the node is 30 wide;
* hull_torus: the hull of a torus (R 10, r 2) met with a box that leaves
  it whole: the disc of radius 10 thickened by 2, length(max(rho - 10, 0),
  z) - 2, exact — its turn cut into wedges, the node 24 wide;
* hull_cut_and_disc: the hull of a cylinder (r 10, h 4) met with a box that
  leaves it whole and a thin cylinder of the same radius above it (z 8 to
  8.5), which the hull takes exactly unless others of its parts are cut:
  the cylinder r 10 from z 0 to 8.5, the exact distance of a capped
  cylinder — the node is 20 wide;
* shadow_ring: the shadow of a ball (r 12) with a round hole (r 5) through
  it, extruded 2: the ring 5 <= rho <= 12, 0 <= z <= 2; max(rho - 12, 5 - rho,
  -z, z - 2), exact inside it and in the hole — the node is 24 wide.

And the plane's approximation (src/plane/flat.rs: a shape flattened to
straight polygons within 1/8192 of its size, then offset, summed or turned
exactly):

* offset_ellipse: an ellipse (semi-axes 10 and 5) grown round by 1.5,
  extruded 2: the points within 1.5 of the ellipse; the distance to the
  ellipse (found by bisection on the foot point's angle, exact to rounding)
  less 1.5, met with the slab — the ellipse is 20 wide;
* turn_lemon: a circle of radius 6 centred 2 left of the axis, its part at
  x >= 0 turned: in the plane through the axis, the lens where the circles
  about (-2, 0) and (2, 0) meet; the larger of their signed distances — the
  circle is 12 wide.

Rays are parallel, along a slanted view direction, through every tenth
pixel of an 800-pixel-wide image centred on a place where the
approximation errs most (a trim of the ball by the box; the hole's rim;
the ring's outer rim), at three zooms: the node 400, 1600 and 4096 pixels
wide. csgrt traces them (--trace-rays); where it hits, the exact signed
distance of its point, in that zoom's pixels, must be under half a pixel;
and csgrt and the exact solid must agree on hit or miss for all but 1 % of
the rays (those that graze the silhouette within the error).

Usage: approximation.py [--csgrt BIN]   (exit 1 on any failure)
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from tools import ROOT

ZOOMS = [400, 1600, 4096]  # pixels across the approximated node
WIDTH, HEIGHT, STEP = 800, 600, 10
LIMIT_PX = 0.5
MISMATCH = 0.01


# Each signed distance takes points as an (n, 3) array.


def box_distance(p, lo, hi):
    """Euclidean distance from each point to the box [lo, hi] (0 inside)."""
    out = np.maximum(np.maximum(np.array(lo) - p, 0.0), p - np.array(hi))
    return np.sqrt((out * out).sum(axis=1))


def hull_ball_box(p):
    return np.maximum(np.sqrt((p * p).sum(axis=1)) - 10.0, np.abs(p).max(axis=1) - 8.0)


PLATE = [
    ((0, 0, 0), (5, 20, 4)),
    ((11, 0, 0), (30, 20, 4)),
    ((5, 0, 0), (11, 5, 4)),
    ((5, 11, 0), (11, 20, 4)),
]


def minkowski_plate(p):
    return np.min([box_distance(p, lo, hi) for lo, hi in PLATE], axis=0) - 1.5


def hull_torus(p):
    rho = np.hypot(p[:, 0], p[:, 1])
    return np.hypot(np.maximum(rho - 10.0, 0.0), p[:, 2]) - 2.0


def hull_cut_and_disc(p):
    rho = np.hypot(p[:, 0], p[:, 1])
    q = np.stack([rho - 10.0, np.abs(p[:, 2] - 4.25) - 4.25], axis=1)
    return np.hypot(*np.maximum(q, 0.0).T) + np.minimum(q.max(axis=1), 0.0)


def shadow_ring(p):
    rho = np.hypot(p[:, 0], p[:, 1])
    return np.max([rho - 12.0, 5.0 - rho, -p[:, 2], p[:, 2] - 2.0], axis=0)


def ellipse_distance(x, y, a, b):
    """Distance from points (x, y) to the ellipse x^2/a^2 + y^2/b^2 = 1
    (a >= b), negative inside: in the first quadrant the nearest point
    (a cos t, b sin t) of a point outside solves
    (a^2 - b^2) cos t sin t - x a sin t + y b cos t = 0, one root in
    [0, pi/2], found by bisection (32 halvings: within 4e-10 radians,
    far under a pixel at any zoom here)."""
    x, y = np.abs(x), np.abs(y)
    lo, hi = np.zeros_like(x), np.full_like(x, math.pi / 2)
    g = lambda t: (a * a - b * b) * np.cos(t) * np.sin(t) - x * a * np.sin(t) + y * b * np.cos(t)
    for _ in range(32):
        mid = 0.5 * (lo + hi)
        pos = g(mid) > 0
        lo, hi = np.where(pos, mid, lo), np.where(pos, hi, mid)
    t = 0.5 * (lo + hi)
    d = np.hypot(x - a * np.cos(t), y - b * np.sin(t))
    inside = (x / a) ** 2 + (y / b) ** 2 <= 1.0
    return np.where(inside, -d, d)


def offset_ellipse(p):
    grown = np.where(
        (p[:, 0] / 10.0) ** 2 + (p[:, 1] / 5.0) ** 2 <= 1.0,
        -1.5,
        ellipse_distance(p[:, 0], p[:, 1], 10.0, 5.0) - 1.5,
    )
    return np.maximum(grown, np.maximum(-p[:, 2], p[:, 2] - 2.0))


def turn_lemon(p):
    rho = np.hypot(p[:, 0], p[:, 1])
    return np.maximum(np.hypot(rho + 2.0, p[:, 2]) - 6.0, np.hypot(rho - 2.0, p[:, 2]) - 6.0)


# name: (scene, signed distance, node size, box (lo, hi) for exact hits,
#        focus point, view direction)
CASES = {
    "hull_ball_box": (
        "hull() intersection() { sphere(r = 10); cube(size = [16, 16, 16], center = true); }\n",
        hull_ball_box,
        16.0,
        ((-8, -8, -8), (8, 8, 8)),
        (8.0, 6.0 / math.sqrt(2), 6.0 / math.sqrt(2)),
        (-0.8, -0.35, -0.5),
    ),
    "minkowski_plate": (
        "minkowski() { difference() { cube(size = [30, 20, 4]);"
        " translate([5, 5, -1]) cube(size = [6, 6, 6]); } sphere(r = 1.5); }\n",
        minkowski_plate,
        30.0,
        ((-1.5, -1.5, -1.5), (31.5, 21.5, 5.5)),
        (6.5, 8.0, 4.0),
        (0.3, 0.2, -0.9),
    ),
    "hull_torus": (
        "hull() intersection() { rotate_extrude() translate([10, 0]) circle(r = 2);"
        " cube(size = [40, 40, 40], center = true); }\n",
        hull_torus,
        24.0,
        ((-12, -12, -2), (12, 12, 2)),
        (12.0 / math.sqrt(2), 12.0 / math.sqrt(2), 0.0),
        (-0.6, -0.5, -0.4),
    ),
    "hull_cut_and_disc": (
        "hull() { intersection() { cylinder(r = 10, h = 4); cube(size = [40, 40, 40], center = true); }"
        " translate([0, 0, 8]) cylinder(r = 10, h = 0.5); }\n",
        hull_cut_and_disc,
        20.0,
        ((-10, -10, 0), (10, 10, 8.5)),
        (10.0 / math.sqrt(2), 10.0 / math.sqrt(2), 8.5),
        (-0.6, -0.5, -0.5),
    ),
    "shadow_ring": (
        "linear_extrude(height = 2) projection(cut = false) difference() { sphere(r = 12);"
        " cylinder(r = 5, h = 40, center = true); }\n",
        shadow_ring,
        24.0,
        ((-12, -12, 0), (12, 12, 2)),
        (12.0 / math.sqrt(2), 12.0 / math.sqrt(2), 2.0),
        (-0.4, -0.5, -0.75),
    ),
    "offset_ellipse": (
        "linear_extrude(height = 2) offset(r = 1.5) scale([2, 1]) circle(r = 5);\n",
        offset_ellipse,
        20.0,
        ((-11.5, -6.5, 0), (11.5, 6.5, 2)),
        (11.5, 0.0, 2.0),
        (-0.5, 0.3, -0.8),
    ),
    "turn_lemon": (
        "rotate_extrude() difference() { translate([-2, 0]) circle(r = 6);"
        " translate([-20, -20]) square([20, 40]); }\n",
        turn_lemon,
        12.0,
        ((-4, -4, -6), (4, 4, 6)),
        (4.0 / math.sqrt(2), 4.0 / math.sqrt(2), 0.0),
        (-0.6, -0.5, -0.4),
    ),
}


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rays_for(size, focus, view, zoom):
    """Parallel rays through every STEP-th pixel of a WIDTH x HEIGHT view
    centred on `focus`, the node `zoom` pixels wide; and the pixel's size."""
    d = unit(view)
    u = unit(cross(d, (0.0, 0.0, 1.0)))
    v = cross(u, d)
    pixel = size / zoom
    back = 4.0 * size
    out = []
    for j in range(0, HEIGHT, STEP):
        for i in range(0, WIDTH, STEP):
            a, b = (i + 0.5 - WIDTH / 2) * pixel, (j + 0.5 - HEIGHT / 2) * pixel
            o = tuple(focus[k] + a * u[k] + b * v[k] - back * d[k] for k in range(3))
            out.append((o, d))
    return out, pixel


def exact_hits(sd, box, rays, pixel):
    """Whether the exact solid meets each ray, by sphere tracing all of them
    at once through the solid's box: each signed distance here is never
    more than the true distance (exact, or a max of exact ones), so a step
    of max(sd, a tenth of a pixel) passes over no part of the solid
    thicker than that tenth."""
    lo, hi = np.array(box[0], float), np.array(box[1], float)
    o = np.array([r[0] for r in rays], float)
    d = np.array([r[1] for r in rays], float)
    with np.errstate(divide="ignore", invalid="ignore"):
        a, b = (lo - o) / d, (hi - o) / d
    a = np.where(d == 0.0, np.where((lo <= o) & (o <= hi), -np.inf, np.inf), a)
    b = np.where(d == 0.0, np.where((lo <= o) & (o <= hi), np.inf, -np.inf), b)
    t0 = np.minimum(a, b).max(axis=1)
    t1 = np.maximum(a, b).min(axis=1)
    hit = np.zeros(len(rays), bool)
    t = t0.copy()
    live = np.flatnonzero(t0 <= t1)
    while live.size:
        e = sd(o[live] + t[live, None] * d[live])
        inside = e <= 0.0
        hit[live[inside]] = True
        t[live] += np.maximum(e, 0.1 * pixel)
        live = live[~inside & (t[live] <= t1[live])]
    return hit


def trace(binary, scene, rays, work):
    path = os.path.join(work, "s.csg")
    with open(path, "w") as f:
        f.write(scene)
    rf = os.path.join(work, "rays.txt")
    with open(rf, "w") as f:
        for o, d in rays:
            f.write(" ".join(repr(x) for x in (*o, *d)) + "\n")
    out = subprocess.run([binary, path, "--trace-rays", rf], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(out.stderr.strip().splitlines()[0] if out.stderr.strip() else "csgrt failed")
    return [None if line == "miss" else float(line.split()[0]) for line in out.stdout.splitlines()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target/release/csgrt"))
    a = ap.parse_args()
    failures = 0
    with tempfile.TemporaryDirectory() as work:
        for name, (scene, sd, size, box, focus, view) in CASES.items():
            for zoom in ZOOMS:
                rays, pixel = rays_for(size, focus, view, zoom)
                try:
                    ts = trace(a.csgrt, scene, rays, work)
                except RuntimeError as e:
                    print(f"FAIL {name} at {zoom} px: {e}")
                    failures += 1
                    continue
                worst, hits, wrong = 0.0, 0, 0
                exacts = exact_hits(sd, box, rays, pixel)
                for (o, d), t, exact in zip(rays, ts, exacts):
                    if t is None:
                        wrong += exact
                        continue
                    hits += 1
                    e = float(sd(np.array([[o[k] + d[k] * t for k in range(3)]]))[0])
                    worst = max(worst, abs(e) / pixel)
                    wrong += not exact and e > pixel * LIMIT_PX
                ok = worst < LIMIT_PX and wrong <= MISMATCH * len(rays) and hits > 0
                failures += not ok
                print(
                    f"{'ok  ' if ok else 'FAIL'} {name}: node {zoom} px wide, {hits} of {len(rays)} rays hit, "
                    f"worst error {worst:.4f} px (limit {LIMIT_PX}), {wrong} disagree on hit or miss"
                )
    print(f"{len(CASES) * len(ZOOMS) - failures} passed, {failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
