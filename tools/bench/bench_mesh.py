#!/usr/bin/env python3
"""csgrt's mesh leaf against Embree and POV-Ray on one big mesh (issue 15).

Generates (once, into bench/mesh/, not kept in git) a gyroid sheet cut by a
ball — manifold3d's level_set of min(0.3 - |g|, R - |p|), g the gyroid —
as a binary STL of about 1.3 million triangles, and a scene importing it
with a fixed camera. Then, on one core (the process and its children bound
to it, csgrt --threads 1, Embree's own threads too):

* primary rays: the same camera rays (pixel centres, csgrt's camera as
  tools/oracle/oracle/ builds it) traced by csgrt (`--trace-rays`, its own
  trace-loop seconds) and by Embree (embreex: rtcIntersect1 per ray, the
  build timed apart; each program's first pass after its build, Embree's
  second pass reported too); the ratio, and the pixels whose hit or miss differ
  (silhouettes), with how many of those lie on a silhouette edge;
Each time is the median of 7 runs; the primary rays' ratio is the median
of 7 rounds' ratios, csgrt and Embree run back to back in each round.

* load: csgrt's whole run on one ray (parse, STL, merge, triangulation,
  BVH) — wall-clock seconds — and its peak resident memory beyond a run
  on an empty scene, per triangle beyond the STL's own 50 bytes;
* full render: csgrt's render_seconds against POV-Ray's Trace Time on the
  same mesh as `mesh2` (csgrt --export-pov), one thread each, shadows on.

Needs tools/requirements-bench.txt (embreex) besides tools/requirements.txt.

Usage: bench_mesh.py [--csgrt BIN] [--size WxH] [--edge 0.41] [--out FILE] [--keep-rays FILE]
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from tools.oracle import oracle  # noqa: E402

from tools import ROOT
DIR = os.path.join(ROOT, "bench", "mesh")
R = 20.0
ROUNDS = 7


def generate(edge):
    import manifold3d as mf

    stl = os.path.join(DIR, "gyroid.stl")
    if os.path.exists(stl):
        return stl

    def f(x, y, z):
        g = math.sin(x) * math.cos(y) + math.sin(y) * math.cos(z) + math.sin(z) * math.cos(x)
        return min(0.3 - abs(g), R - math.sqrt(x * x + y * y + z * z))

    m = mf.Manifold.level_set(f, [-R - 1] * 3 + [R + 1] * 3, edge)
    mesh = m.to_mesh()
    v = np.asarray(mesh.vert_properties, dtype=np.float32)[:, :3]
    t = np.asarray(mesh.tri_verts)
    os.makedirs(DIR, exist_ok=True)
    rec = np.zeros(len(t), dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    rec["v"] = v[t]
    with open(stl, "wb") as fh:
        fh.write(b"gyroid sheet in a ball, tools/bench/bench_mesh.py".ljust(80, b" "))
        fh.write(np.uint32(len(t)).tobytes())
        fh.write(rec.tobytes())
    with open(os.path.join(DIR, "gyroid.csg"), "w") as fh:
        fh.write("camera(eye = [52, -64, 40], lookat = [0, 0, 0], fov = 38);\nimport(\"gyroid.stl\");\n")
    with open(os.path.join(DIR, "empty.csg"), "w") as fh:
        fh.write("camera(eye = [52, -64, 40], lookat = [0, 0, 0], fov = 38);\ncube(1);\n")
    return stl


# Run by a fresh, small Python: forks and execs the command (its output to
# /dev/null), then prints wall seconds, the child's peak RSS and its exit
# status. Linux keeps a child's peak RSS through fork and exec starting
# from its parent's, and this process holds the whole mesh for Embree: a
# child of it would report at least that.
_MEASURE = r"""
import os, sys, time
t = time.perf_counter()
pid = os.fork()
if pid == 0:
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.dup2(null, 2)
    os.execvp(sys.argv[1], sys.argv[1:])
_, status, ru = os.wait4(pid, 0)
print(time.perf_counter() - t, ru.ru_maxrss * 1024, os.waitstatus_to_exitcode(status))
"""


def child_run(cmd):
    """(wall seconds, peak RSS in bytes) of one child process, measured by
    a small process of its own (see _MEASURE)."""
    out = subprocess.run([sys.executable, "-c", _MEASURE, *cmd], check=True,
                         capture_output=True, text=True).stdout.split()
    wall, rss, code = float(out[0]), int(out[1]), int(out[2])
    if code != 0:
        raise subprocess.CalledProcessError(code, cmd)
    return wall, rss


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target/release/csgrt"))
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--edge", type=float, default=0.41)
    ap.add_argument("--out")
    ap.add_argument("--keep-rays", help="also write the camera rays here (for examples/mesh_rays.rs)")
    a = ap.parse_args()
    # One core for everything, Embree's threads included (children inherit).
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    w, h = map(int, a.size.split("x"))
    stl = generate(a.edge)
    ntri = (os.path.getsize(stl) - 84) // 50
    scene = os.path.join(DIR, "gyroid.csg")
    one = []
    rows = []
    with tempfile.TemporaryDirectory() as work:
        dump = os.path.join(work, "d.json")
        subprocess.run([a.csgrt, scene, "--size", a.size, "--dump-scene", dump, "-o", os.path.join(work, "x.png"), "-q"], check=True)
        cam = json.load(open(dump))["camera"]
        rays = oracle.camera_rays((cam["eye"], cam["lookat"], cam["up"], cam["fov"]), w, h)
        rfile = os.path.join(work, "rays.txt")
        with open(rfile, "w") as fh:
            for o, d in rays:
                fh.write("%r %r %r %r %r %r\n" % tuple(float(x) for x in (*o, *d)))
        if a.keep_rays:
            import shutil

            shutil.copyfile(rfile, a.keep_rays)
        one_ray = os.path.join(work, "one.txt")
        with open(one_ray, "w") as fh:
            fh.write("%r %r %r %r %r %r\n" % tuple(float(x) for x in (*rays[0][0], *rays[0][1])))
        # Load and build, and memory: one ray, against the empty scene.
        empty_wall, empty_rss = child_run(one + [a.csgrt, os.path.join(DIR, "empty.csg"), "--trace-rays", one_ray, "--threads", "1"])
        # Timings are the median of ROUNDS runs (this is a noisy machine).
        loads = [child_run(one + [a.csgrt, scene, "--trace-rays", one_ray, "--threads", "1"]) for _ in range(ROUNDS)]
        load_wall = statistics.median(x[0] for x in loads)
        load_rss = max(x[1] for x in loads)
        beyond = (load_rss - empty_rss - 50 * ntri) / ntri
        # Primary rays: csgrt and Embree on the same triangles and rays, one
        # after the other in each round, so that both meet the same phase of
        # a machine whose speed drifts by 10 to 20 % from one minute to the
        # next; the ratio is the median of the rounds' own ratios.
        st = os.path.join(work, "st.json")
        hits = os.path.join(work, "hits.txt")
        from embreex import rtcore_scene as rtcs
        from embreex.mesh_construction import TriangleMesh

        rec = np.fromfile(stl, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), offset=84)
        tris = rec["v"].astype(np.float32)
        origins = np.array([o for o, _ in rays], dtype=np.float32)
        dirs = np.array([d for _, d in rays], dtype=np.float32)
        traces = []
        # Like csgrt's, each of Embree's timed passes is the first over the
        # rays after its build (a fresh scene each round): both programs
        # begin with their hierarchies out of the caches. A second pass over
        # the same scene (caches warm from the first) is reported too.
        embree_builds, embree_traces, embree_warm = [], [], []
        for _ in range(ROUNDS):
            with open(hits, "w") as out:
                subprocess.run(one + [a.csgrt, scene, "--trace-rays", rfile, "--threads", "1", "--stats-json", st], check=True, stdout=out)
            traces.append(json.load(open(st))["render_seconds"])
            es = None
            t0 = time.perf_counter()
            es = rtcs.EmbreeScene()
            TriangleMesh(es, tris)
            es.run(origins[:1], dirs[:1])  # the build happens at the first query
            embree_builds.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            ids = es.run(origins, dirs)
            embree_traces.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            es.run(origins, dirs)
            embree_warm.append(time.perf_counter() - t0)
        csgrt_trace = statistics.median(traces)
        mine = [line.split()[0] != "miss" for line in open(hits)]
        embree_build = statistics.median(embree_builds)
        embree_trace = statistics.median(embree_traces)
        warm = statistics.median(embree_warm)
        ratios = sorted(c / e for c, e in zip(traces, embree_traces))
        warm_ratios = sorted(c / e for c, e in zip(traces, embree_warm))
        theirs = list(np.asarray(ids) >= 0)
        grid = np.array(mine).reshape(h, w)
        diff = np.array(mine) != np.array(theirs)
        edge = oracle.mixed(np.where(grid, 1, -1)).reshape(-1) if hasattr(oracle, "mixed") else np.zeros(len(mine), bool)
        # Full render against POV-Ray's mesh2.
        pov = os.path.join(work, "g.pov")
        subprocess.run(one + [a.csgrt, scene, "--size", a.size, "--threads", "1", "--spp", "1", "--stats-json", st, "--export-pov", pov, "-o", os.path.join(work, "g.png"), "-q"], check=True)
        render = json.load(open(st))["render_seconds"]
        r = subprocess.run(one + ["povray", f"+I{pov}", f"+O{os.path.join(work, 'p.png')}", f"+W{w}", f"+H{h}", "+FN", "-D", "+WT1"], capture_output=True, text=True)
        pov_trace = next(float(x.split("(")[1].split()[0]) for x in r.stderr.splitlines() if "Trace Time:" in x)
        parse = next((float(x.split("(")[1].split()[0]) for x in r.stderr.splitlines() if "Parse Time:" in x), float("nan"))
    rows = [
        f"triangles: {ntri} ({os.path.getsize(stl) / 1e6:.1f} MB binary STL), {w}x{h} camera rays, one core",
        f"primary rays: csgrt {csgrt_trace:.3f} s, Embree {embree_trace:.3f} s (rtcIntersect1 per ray through embreex; medians), ratio {statistics.median(ratios):.2f} (median of the rounds' ratios, {ratios[0]:.2f} to {ratios[-1]:.2f}; each program's first pass after its build)",
        f"primary rays, Embree's second pass over the same scene: {warm:.3f} s, ratio {statistics.median(warm_ratios):.2f} ({warm_ratios[0]:.2f} to {warm_ratios[-1]:.2f})",
        f"silhouettes: {int(diff.sum())} of {len(mine)} pixels differ in hit or miss, {int((diff & edge).sum())} of them on csgrt's silhouette edge",
        f"load (parse, STL, merge, BVH) + one ray: csgrt {load_wall:.3f} s wall (an empty scene: {empty_wall:.3f} s); Embree's build alone {embree_build:.3f} s",
        f"memory: peak RSS {load_rss / 1e6:.0f} MB, {beyond:.0f} bytes a triangle beyond the empty run and the STL's 50",
        f"full render (shadows): csgrt {render:.3f} s, POV-Ray mesh2 trace {pov_trace:.3f} s (parse {parse:.3f} s), ratio {render / pov_trace:.2f}",
    ]
    text = "\n".join(rows)
    print(text)
    if a.out:
        with open(a.out, "w") as fh:
            fh.write(text + "\n")


if __name__ == "__main__":
    main()
