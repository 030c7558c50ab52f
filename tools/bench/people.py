#!/usr/bin/env python3
"""People's models (bench/people/) timed as a user runs csgrt, beside OpenSCAD's
CGAL render and manifold3d's mesh and raster of the same files (issue 45).

    python -m tools.bench.people [--csgrt BIN] [--arg ARG ...] [--against BIN] [--limit 120] [--json F] [--out F] [FILE...]

For each export (every `.csg` under bench/people/ unless files are given),
each on its own, one after another:

* csgrt: the whole process, `csgrt -q -o x.png model.csg`: 800×600, its
  default settings (adaptive anti-aliasing, every core); the median of 3
  runs when the first takes under a second;
* OpenSCAD 2021.01's CGAL render: the whole process, `openscad -o x.off
  model.csg` (`x.svg` for a model that is 2-D at its top);
* manifold3d: the Python oracle's reader meshes the same tree with
  manifold3d (every circle of 64 segments, its booleans batched; the time to
  mesh), then Embree (embreex) casts the 800×600 pixel-centre rays of
  csgrt's camera at that mesh (build and cast): mesh + raster, in a child
  process. The oracle's reader does not read every statement; a model it
  refuses has no manifold time.

Each program gets `--limit` seconds (a run that takes longer is reported as
over the limit). Prints the table and the distribution; `--out` writes
them as Markdown, `--json` every model's numbers.
"""

import argparse
import glob
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

from tools import ROOT

SIZE = (800, 600)
SEGMENTS = 64


def timed(cmd, limit, cwd=None):
    """(wall seconds, None) or (None, why)."""
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=limit, cwd=cwd)
    except subprocess.TimeoutExpired:
        return None, f"over {limit:g} s"
    took = time.perf_counter() - t0
    if p.returncode:
        line = (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
        return None, line[:100]
    return took, None


def csgrt_time(csgrt, model, work, limit):
    return builds_times([csgrt], model, work, limit)[0]


def builds_times(builds, model, work, limit, lead=0):
    """Each build's (t, why) for `csgrt -q -o x.png model`: one run, and
    where it took under a second the median of 3, a failed rerun counting
    as the first. A build is a path, or a list: the path and arguments
    added to its command line. Several builds' runs alternate — this
    machine's speed drifts by tens of percent over minutes, so builds
    timed in runs apart cannot be compared — and which runs first turns
    with each round, starting from build `lead`: a run right after another
    build's is not the same as one after its own (the same binary against
    itself read 0.969 when the first always led), so a caller passes a
    different `lead` model by model and neither build leads more often."""
    png = os.path.join(work, "c.png")
    cmds = [([b] if isinstance(b, str) else list(b)) + ["-q", "-o", png, model] for b in builds]
    n = len(cmds)
    first, runs = [None] * n, [[] for _ in cmds]
    for r in range(3):
        for k in range(n):
            i = (lead + r + k) % n
            if r == 0:
                first[i] = timed(cmds[i], limit)
                runs[i].append(first[i][0])
            elif first[i][0] is not None and first[i][0] < 1.0:
                runs[i].append(timed(cmds[i], limit)[0] or first[i][0])
    return [(statistics.median(got), None) if t is not None else (None, why) for (t, why), got in zip(first, runs)]


def openscad_time(model, work, limit):
    t, why = timed(["openscad", "-o", os.path.join(work, "o.off"), model], limit, cwd=os.path.dirname(model))
    if why and "not a 3D object" in why or why and "top level object is a 2D" in why:
        t, why = timed(["openscad", "-o", os.path.join(work, "o.svg"), model], limit, cwd=os.path.dirname(model))
    return t, why


def manifold_child(model, camera):
    """In the child: mesh with manifold3d, cast with Embree; prints JSON."""
    import numpy as np

    from tools.oracle import scene as reader
    from tools.oracle.oracle import cast, ray_sets

    t0 = time.perf_counter()
    sc = reader.read(model)
    solid = cast.Caster(sc, SEGMENTS).solid
    m = solid.to_mesh()
    mesh_s = time.perf_counter() - t0
    from embreex import rtcore_scene as rtcs
    from embreex.mesh_construction import TriangleMesh

    with open(camera) as f:
        cam = json.load(f)["camera"]
    rays = ray_sets.camera_rays((cam["eye"], cam["lookat"], cam["up"], cam["fov"]), *SIZE)
    origins = np.array([o for o, _ in rays], dtype=np.float32)
    dirs = np.array([d for _, d in rays], dtype=np.float32)
    verts = np.asarray(m.vert_properties, dtype=np.float32)[:, :3]
    tris = verts[np.asarray(m.tri_verts, dtype=np.int64)]
    t0 = time.perf_counter()
    if len(tris):
        es = rtcs.EmbreeScene()
        TriangleMesh(es, tris)
        es.run(origins, dirs)
    raster_s = time.perf_counter() - t0
    print(json.dumps({"mesh": mesh_s, "raster": raster_s, "triangles": len(tris)}))


def manifold_time(csgrt, model, work, limit):
    camera = os.path.join(work, "scene.json")
    p = subprocess.run(
        [csgrt, "-q", "--size", "8x6", "--spp", "1", "-o", os.path.join(work, "d.png"), "--dump-scene", camera, model],
        capture_output=True,
    )
    if p.returncode:
        return None, "no camera"
    try:
        p = subprocess.run(
            [sys.executable, "-m", "tools.bench.people", "--manifold-child", model, camera],
            capture_output=True,
            text=True,
            timeout=limit,
            cwd=ROOT,
        )
    except subprocess.TimeoutExpired:
        return None, f"over {limit:g} s"
    if p.returncode:
        return None, ((p.stderr.strip().splitlines() or ["failed"])[-1])[:100]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    return r["mesh"] + r["raster"], None


def percentile(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, max(0, math.ceil(q * len(xs)) - 1))]


def fmt(t, why, limit):
    """A time, "> N s" for a run stopped at its limit, or "—" for none."""
    if t is not None:
        return f"{t:.3f} s"
    return "> " + why[len("over ") :] if why and why.startswith("over") else "—"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target/release/csgrt"))
    ap.add_argument("--limit", type=float, default=120.0)
    ap.add_argument("--json")
    ap.add_argument("--out")
    ap.add_argument("--skip", default="", help="comma-separated: csgrt, openscad, manifold")
    ap.add_argument(
        "--reuse",
        help="an earlier run's --json: the columns skipped now are taken from it (OpenSCAD's "
        "and manifold's times do not change with csgrt's build)",
    )
    ap.add_argument(
        "--against",
        help="another csgrt build, timed beside this one model by model (their runs alternated): "
        "the ratio of each model's times and their distribution",
    )
    ap.add_argument(
        "--arg",
        action="append",
        default=[],
        help="an argument added to this build's command line only (repeatable; `--arg=--spp --arg=1` "
        "with `--against` the same build: what default anti-aliasing costs)",
    )
    ap.add_argument("--manifold-child", nargs=2, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.manifold_child:
        manifold_child(*a.manifold_child)
        return 0
    files = a.files or sorted(glob.glob(os.path.join(ROOT, "bench/people/**/*.csg"), recursive=True))
    skip = set(filter(None, a.skip.split(",")))
    csgrt = [os.path.abspath(a.csgrt)] + a.arg
    earlier = {}
    if a.reuse:
        with open(a.reuse) as f:
            earlier = {r["model"]: r for r in json.load(f)}
    rows = []
    for index, model in enumerate(files):
        model = os.path.abspath(model)
        name = os.path.relpath(model, os.path.join(ROOT, "bench/people"))
        old = earlier.get(name, {})

        def kept(key):
            return old.get(key), old.get(key + "_why", "skipped")

        with tempfile.TemporaryDirectory(prefix="people") as work:
            before = (None, "not asked")
            if a.against:
                c, before = builds_times([csgrt, os.path.abspath(a.against)], model, work, a.limit, lead=index)
            else:
                c = kept("csgrt") if "csgrt" in skip else csgrt_time(csgrt, model, work, a.limit)
            o = kept("openscad") if "openscad" in skip else openscad_time(model, work, a.limit)
            m = kept("manifold") if "manifold" in skip else manifold_time(csgrt[0], model, work, a.limit)
        row = {"model": name, "csgrt": c[0], "csgrt_why": c[1], "openscad": o[0], "openscad_why": o[1], "manifold": m[0], "manifold_why": m[1]}
        if a.against:
            row.update(against=before[0], against_why=before[1])
        rows.append(row)
        print(f"{name}: csgrt {fmt(*c, a.limit)} ({c[1] or 'ok'}), OpenSCAD {fmt(*o, a.limit)}, manifold {fmt(*m, a.limit)} ({m[1] or 'ok'})", file=sys.stderr, flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)
    text = report(rows, a.limit)
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    return 0


def report(rows, limit):
    # A model csgrt did not finish counts at the limit in the distribution.
    ts = [r["csgrt"] if r["csgrt"] is not None else limit for r in rows]
    done = [r for r in rows if r["csgrt"] is not None]
    both_o = [r for r in done if r["openscad"] is not None]
    both_m = [r for r in done if r["manifold"] is not None]
    slower_o = [r for r in both_o if r["csgrt"] >= r["openscad"]]
    slower_m = [r for r in both_m if r["csgrt"] >= r["manifold"]]
    lines = [
        f"{len(rows)} models; csgrt finished {len(done)} (the rest count at {limit:g} s): "
        f"median {statistics.median(ts):.3f} s, 90th percentile {percentile(ts, 0.9):.3f} s, "
        f"slowest {max(ts):.3f} s; {sum(t > 2 for t in ts)} over 2 s, {sum(t > 0.25 for t in ts)} over 0.25 s, "
        f"{sum(t <= 0.05 for t in ts)} within 0.05 s.",
        "",
        f"Against OpenSCAD's CGAL render ({len(both_o)} models both finished): csgrt slower on {len(slower_o)}"
        + (f" ({', '.join(r['model'] for r in slower_o)})" if slower_o else "")
        + (f"; geometric mean of csgrt / OpenSCAD {gmean([r['csgrt'] / r['openscad'] for r in both_o]):.3f}" if both_o else "")
        + f"; OpenSCAD stopped at its limit on {sum(1 for r in rows if (r['openscad_why'] or '').startswith('over'))}"
        + f" and failed on {sum(1 for r in rows if r['openscad'] is None and not (r['openscad_why'] or '').startswith('over'))}.",
        "",
        f"Against manifold3d's mesh and raster ({len(both_m)} models both finished): csgrt slower on {len(slower_m)}"
        + (f" ({', '.join(r['model'] for r in slower_m)})" if slower_m else "")
        + (f"; geometric mean of csgrt / manifold {gmean([r['csgrt'] / r['manifold'] for r in both_m]):.3f}" if both_m else "")
        + f"; the oracle's reader refused or manifold failed on {sum(1 for r in rows if r['manifold'] is None)}.",
        "",
        "| model | csgrt | OpenSCAD CGAL | ratio | manifold3d mesh + raster | ratio |",
        "|---|---|---|---|---|---|",
    ]
    paired = [r for r in done if r.get("against")]
    if paired:
        ratios = sorted((r["csgrt"] / r["against"], r["model"]) for r in paired)
        before = [r["against"] if r["against"] is not None else limit for r in rows if "against" in r]
        lines[-2:-2] = [
            f"Against the other build, timed beside it ({len(paired)} models both finished): geometric mean of "
            f"this / that {gmean([x for x, _ in ratios]):.3f}; this faster by more than 10 % on "
            f"{sum(x < 1 / 1.1 for x, _ in ratios)}, slower by more than 10 % on {sum(x > 1.1 for x, _ in ratios)}"
            + "".join(f"; {m} {x:.3f}" for x, m in ratios if x > 1.1)
            + f". That build's median {statistics.median(before):.3f} s, 90th percentile {percentile(before, 0.9):.3f} s, "
            f"{sum(t > 2 for t in before)} over 2 s. Most changed: "
            + ", ".join(f"{m} {x:.3f}" for x, m in ratios[:5])
            + ".",
            "",
        ]
    for r in sorted(rows, key=lambda r: -(r["csgrt"] if r["csgrt"] is not None else limit)):
        ro = f"{r['csgrt'] / r['openscad']:.3f}" if r["csgrt"] is not None and r["openscad"] else ""
        rm = f"{r['csgrt'] / r['manifold']:.3f}" if r["csgrt"] is not None and r["manifold"] else ""
        lines.append(
            f"| {r['model']} | {fmt(r['csgrt'], r['csgrt_why'], limit)} | {fmt(r['openscad'], r['openscad_why'], limit)} | {ro} "
            f"| {fmt(r['manifold'], r['manifold_why'], limit)} | {rm} |"
        )
    return "\n".join(lines) + "\n"


def gmean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs))


if __name__ == "__main__":
    sys.exit(main())
