#!/usr/bin/env python3
"""The certified approximation's time beside the exact path's, same solid.

Each pair in tests/approximated/pairs/ is one solid written twice: as a
hull, Minkowski sum or shadow of a combination (NAME_approximated.csg,
which csgrt cuts into convex polytopes) and as the same solid by an exact
path (NAME_exact.csg: the cut ball itself, the sum of the plate's four
boxes, the ring as a 2-D difference, the offset shadow of a cylinder as
the circle it is, the turned shadow of a ball as the turned circle). Each
file is rendered as a user
renders it (800x600, default settings, every core, the whole process),
alternating, RUNS times; the table gives the medians and their ratio.

Usage: approximation_pairs.py [--csgrt BIN] [--runs N]
"""

import argparse
import glob
import os
import statistics
import subprocess
import tempfile
import time

from tools import ROOT


def timed(binary, path, out):
    t = time.perf_counter()
    subprocess.run([binary, path, "-o", out, "-q"], check=True, capture_output=True)
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target/release/csgrt"))
    ap.add_argument("--runs", type=int, default=5)
    a = ap.parse_args()
    pairs = sorted(p[: -len("_approximated.csg")] for p in glob.glob(os.path.join(ROOT, "tests/approximated/pairs/*_approximated.csg")))
    print("| solid | approximated | exact | ratio |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "x.png")
        for base in pairs:
            times = {"approximated": [], "exact": []}
            for _ in range(a.runs):
                for kind in times:
                    times[kind].append(timed(a.csgrt, f"{base}_{kind}.csg", out))
            ta, te = (statistics.median(times[k]) for k in ("approximated", "exact"))
            print(f"| {os.path.basename(base)} | {ta:.3f} s | {te:.3f} s | {ta / te:.2f} |")


if __name__ == "__main__":
    main()
