#!/usr/bin/env python3
"""How far default anti-aliasing leaves people's models from their converged
pictures, build beside build: the error a sampler and a sample count buy.

    python -m tools.bench.aa_error [--csgrt BIN ...] [--every 5] [--under 0.1]
                                   [--size 400x300] [--reference-spp 256] [FILE...]

Models: every `--every`-th export under bench/people/ (sorted; or the files
given) whose one-sample picture at `--size` renders in under `--under`
seconds (the reference costs `--reference-spp` times that). For each model:

* the reference: the first build at `--spp N`, N = `--reference-spp`, every
  pixel — the picture anti-aliasing converges to;
* edge pixels: those where the reference and the first build's `--spp 1`
  picture differ by more than 2 (of 255) in a channel — where sampling
  matters, chosen by neither build's own decisions;
* each build at its default settings (adaptive anti-aliasing), with
  `--stats-json` for its primary rays.

Prints, for each build, the RMS error in 8-bit levels over the edge pixels
and over every pixel (pooled over the models), and its primary rays in all:
error against work. Builds whose adaptive pass picks the same pixels (the
choice depends on pixel centres and corners only) differ only in how well
their refined pixels converge.
"""

import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from PIL import Image

from tools import ROOT


def render(binary, model, out, size, extra, stats=None):
    cmd = [binary, "-q", "--size", size, "-o", out, *extra, model]
    if stats:
        cmd += ["--stats-json", stats]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, cwd=os.path.dirname(model))
    return time.perf_counter() - t0


def pixels(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*")
    ap.add_argument("--csgrt", action="append", help="a build (repeat for several; default target/release/csgrt)")
    ap.add_argument("--every", type=int, default=5)
    ap.add_argument("--under", type=float, default=0.1)
    ap.add_argument("--size", default="400x300")
    ap.add_argument("--reference-spp", type=int, default=256)
    a = ap.parse_args()
    builds = [os.path.abspath(b) for b in (a.csgrt or [os.path.join(ROOT, "target/release/csgrt")])]
    files = a.files or sorted(glob.glob(os.path.join(ROOT, "bench/people/**/*.csg"), recursive=True))[:: a.every]
    files = [os.path.abspath(f) for f in files]
    sq_edge = [0.0] * len(builds)
    sq_all = [0.0] * len(builds)
    rays = [0] * len(builds)
    n_edge = n_all = used = 0
    with tempfile.TemporaryDirectory() as work:
        one, ref = os.path.join(work, "one.png"), os.path.join(work, "ref.png")
        for model in files:
            name = os.path.relpath(model, os.path.join(ROOT, "bench/people"))
            try:
                took = render(builds[0], model, one, a.size, ["--spp", "1"])
            except subprocess.CalledProcessError:
                print(f"{name}: not rendered, left out", file=sys.stderr)
                continue
            if took >= a.under:
                continue
            render(builds[0], model, ref, a.size, ["--spp", str(a.reference_spp)])
            r = pixels(ref)
            edge = (np.abs(r - pixels(one)).max(axis=2) > 2.0)
            n_edge += int(edge.sum())
            n_all += edge.size
            used += 1
            line = []
            for i, b in enumerate(builds):
                img, st = os.path.join(work, f"b{i}.png"), os.path.join(work, f"b{i}.json")
                render(b, model, img, a.size, [], st)
                d2 = ((pixels(img) - r) ** 2).sum(axis=2) / 3.0
                sq_edge[i] += float(d2[edge].sum())
                sq_all[i] += float(d2.sum())
                with open(st) as f:
                    rays[i] += json.load(f)["primary_rays"]
                line.append(f"{np.sqrt(d2[edge].mean()) if edge.any() else 0.0:.2f}")
            print(f"{name}: {int(edge.sum())} edge pixels; RMS over them {' / '.join(line)}", file=sys.stderr, flush=True)
    print(f"{used} models at {a.size}, reference {a.reference_spp} spp; {n_edge} edge pixels of {n_all}")
    for i, b in enumerate(builds):
        print(
            f"{b}: RMS error {np.sqrt(sq_edge[i] / max(n_edge, 1)):.3f} over edge pixels, "
            f"{np.sqrt(sq_all[i] / max(n_all, 1)):.4f} over all; {rays[i]} primary rays"
        )


if __name__ == "__main__":
    main()
