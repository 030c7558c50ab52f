#!/usr/bin/env python3
"""Does csgrt's OpenSCAD camera show what OpenSCAD shows?

Renders models of boxes (exact in OpenSCAD's mesh too) with OpenSCAD's own
PNG export (`openscad -o x.png`, under `xvfb-run` when there is no
display) and with csgrt, for each set of camera options (`--camera` in both
forms, `--viewall`, `--autocenter`, `--projection`), and compares where
the model is: OpenSCAD's pixels that are not its background colour
(Cornfield, #ffffe5) against csgrt's hit mask. A pixel that differs counts
as a miss unless it lies on an edge, i.e. its 3×3 neighbourhood is mixed in
either image.

Needs `openscad` (Debian: apt-get install -y openscad xvfb). Not part of
the CI line, which checks the same camera against OpenGL's pipeline written
out in tests/it/camera.rs.

Usage: openscad_view.py [--csgrt BIN]   (exit 1 on any miss)
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image
from tools import ROOT

MODELS = {
    "boxes": """
translate([10, -4, 7]) cube([6, 3, 2]);
translate([-5, 2, -3]) cube(4, center = true);
rotate([0, 0, 30]) cube([2, 8, 1]);
""",
    "tower": """
difference() { cube([10, 10, 30]); translate([2, 2, -1]) cube([6, 6, 40]); }
translate([20, 0, 0]) cube(3);
""",
}

# (Without any of these options csgrt frames the scene its own way, closer
# than OpenSCAD's default view; `--viewall` asks for OpenSCAD's.)
OPTIONS = [
    ["--viewall"],
    ["--camera=3,1,2,60,0,35,80"],
    ["--camera=3,1,2,60,20,-140,60"],
    ["--camera=40,-50,30,2,1,0"],
    ["--camera=1,1,90,1,1,0"],
    ["--camera=3,1,2,60,0,35,80", "--projection=o"],
    ["--camera=3,1,2,60,0,35,20", "--viewall"],
    ["--camera=3,1,2,60,0,35,20", "--viewall", "--autocenter"],
    ["--projection=ortho", "--viewall"],
]

SIZE = (320, 240)


def openscad_cmd():
    exe = shutil.which("openscad")
    if not exe:
        sys.exit("openscad is not on PATH (Debian: apt-get install -y openscad xvfb)")
    if os.environ.get("DISPLAY"):
        return [exe]
    xvfb = shutil.which("xvfb-run")
    if not xvfb:
        sys.exit("no display and no xvfb-run (Debian: apt-get install -y xvfb)")
    return [xvfb, "-a", exe]


def mixed(a):
    """Pixels whose 3×3 neighbourhood holds both values."""
    p = np.pad(a, 1, mode="edge")
    lo = np.ones_like(a)
    hi = np.zeros_like(a)
    h, w = a.shape
    for dy in range(3):
        for dx in range(3):
            n = p[dy:dy + h, dx:dx + w]
            lo = lo & n
            hi = hi | n
    return lo != hi


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    a = ap.parse_args()
    scad = openscad_cmd()
    bad = 0
    with tempfile.TemporaryDirectory() as work:
        for name, text in MODELS.items():
            src = os.path.join(work, name + ".scad")
            with open(src, "w") as f:
                f.write(text)
            csg = os.path.join(work, name + ".csg")
            subprocess.run(scad + ["-o", csg, src], check=True, capture_output=True)
            for opts in OPTIONS:
                png = os.path.join(work, "o.png")
                subprocess.run(scad + ["-o", png, "--imgsize=%d,%d" % SIZE] + opts + [src],
                               check=True, capture_output=True)
                o = np.asarray(Image.open(png).convert("RGB")).astype(int)
                theirs = np.any(o != np.array([255, 255, 229]), axis=2)
                mask = os.path.join(work, "m.png")
                subprocess.run([a.csgrt, csg, "-q", "--size", "%dx%d" % SIZE, "-o",
                                os.path.join(work, "c.png"), "--mask", mask] + opts, check=True)
                ours = np.asarray(Image.open(mask)) > 127
                differ = theirs != ours
                edge = mixed(theirs) | mixed(ours)
                misses = int(np.sum(differ & ~edge))
                bad += misses > 0
                print("%-6s %-45s object %5d px (OpenSCAD %5d), differing %4d, off the edge %d"
                      % (name, " ".join(opts) or "(default)", int(ours.sum()), int(theirs.sum()),
                         int(differ.sum()), misses))
    print("%d of %d views differ off the edges" % (bad, len(MODELS) * len(OPTIONS)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
