#!/usr/bin/env python3
"""The `.scad` loop against OpenSCAD itself: `$t`, `$vp*` and one camera.

    python -m tools.oracle.scad_loop [--csgrt BIN]

Runs csgrt on the programs in tests/scad_loop/ with the real `openscad` on
PATH (2021.01) exporting them, and checks what it draws against closed
forms and csgrt's own renders of hand-written CSG, never against csgrt's
earlier output:

- turn.scad, `a = 360 * $t; rotate([0, 0, a]) …` with `--animate 4` under
  a fixed `--camera`: frame i is byte for byte the render of the bar turned
  by 90·i degrees, written out here (OpenSCAD's `--animate` sets `$t` before
  the program's assignments; `-D $t=…` would come after them, and every
  frame would be frame 0).
- view_all.scad, view_distance.scad: the camera OpenSCAD's gimbal gives
  for the program's `$vpr`, `$vpt`, `$vpd` (the eye `$vpd` from `$vpt`,
  along Rz(rz)·Rx(rx)·(0, 0, 1); OpenSCAD's default [55, 0, 25], 140 and
  the origin for what the program leaves alone); `--camera` overrides them.
  no_view.scad: no OpenSCAD camera, and no notice about `$vp*`.
- slide.scad with `--animate 4`: one camera for every frame. A still cube
  and a ball moving away: frame i is byte for byte csgrt's render of frame
  i written out with an explicit `camera(…)`, the one --dump-scene gives
  for the box of all the frames (the cube and the ball's first and last
  places written out).
- OpenSCAD's own examples/Advanced/animation.scad (its `$t` in top-level
  assignments), `--animate 8`: eight different frames.

Exit status 1 on any failure; an `openscad` that cannot run is a failure.
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

from tools import ROOT

LOOP = os.path.join(ROOT, "tests", "scad_loop")
EXAMPLES = "/usr/share/openscad/examples"
SIZE = "120x90"
CAMERA = "0,0,0,55,0,25,140"
TOL = 1e-9


def run(binary, args, cwd):
    r = subprocess.run([binary, *args], cwd=cwd, capture_output=True, text=True, timeout=300)
    return r.returncode, r.stderr


def read(path):
    with open(path, "rb") as f:
        return f.read()


def rz(deg):
    """The rotation matrix of `rotate([0, 0, deg])` for deg a multiple of
    90, exact."""
    c = {0: 1, 90: 0, 180: -1, 270: 0}[deg % 360]
    s = {0: 0, 90: 1, 180: 0, 270: -1}[deg % 360]
    return [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]


def matrix(m):
    return "[" + ", ".join("[" + ", ".join(str(v) for v in row) + "]" for row in m) + "]"


def check_turn(binary, work, fail):
    d = os.path.join(work, "turn")
    os.makedirs(d)
    code, said = run(binary, [os.path.join(LOOP, "turn.scad"), "--animate", "4", "--camera", CAMERA,
                              "--size", SIZE, "-q", "-O", d], work)
    if code != 0:
        return fail(f"turn.scad --animate 4: exit {code}: {said}")
    frames = [read(os.path.join(d, f"turn{i:05}.png")) for i in range(4)]
    for i in range(4):
        csg = os.path.join(d, f"hand{i}.csg")
        with open(csg, "w") as f:
            f.write(f"multmatrix({matrix(rz(90 * i))}) {{\n\tcube(size = [20, 4, 4], center = false);\n}}\n")
        code, said = run(binary, [csg, "--camera", CAMERA, "--size", SIZE, "-q", "-o", f"hand{i}.png"], d)
        if code != 0:
            return fail(f"hand{i}.csg: exit {code}: {said}")
        if read(os.path.join(d, f"hand{i}.png")) != frames[i]:
            fail(f"turn.scad frame {i} is not the bar turned by {90 * i} degrees")
    if len(set(frames)) != 4:
        fail("turn.scad: frames repeat")
    print("turn.scad: checked, 4 frames against the bar turned by 90 i degrees")


def eye_of(vpr, vpt, vpd):
    rx, rzd = math.radians(vpr[0]), math.radians(vpr[2])
    along = (math.sin(rzd) * math.sin(rx), -math.cos(rzd) * math.sin(rx), math.cos(rx))
    return [t + vpd * a for t, a in zip(vpt, along)]


def camera_of(binary, model, work, extra=()):
    dump = os.path.join(work, "d.json")
    code, said = run(binary, [model, "--size", SIZE, "-q", "--dump-scene", dump, "-o", "v.png", *extra], work)
    if code != 0:
        raise RuntimeError(f"{os.path.basename(model)}: exit {code}: {said}")
    with open(dump) as f:
        return json.load(f)["camera"], said


def check_views(binary, work, fail):
    cases = [
        ("view_all.scad", [60, 0, 30], [5, -2, 1], 80),
        ("view_distance.scad", [55, 0, 25], [0, 0, 0], 200),
    ]
    for name, vpr, vpt, vpd in cases:
        cam, said = camera_of(binary, os.path.join(LOOP, name), work)
        want = eye_of(vpr, vpt, vpd)
        if said:
            fail(f"{name}: csgrt said {said!r}")
        if max(abs(a - b) for a, b in zip(cam["eye"], want)) > TOL or \
                max(abs(a - b) for a, b in zip(cam["lookat"], vpt)) > TOL:
            fail(f"{name}: eye {cam['eye']} looking at {cam['lookat']}; OpenSCAD's gimbal: {want} at {vpt}")
        # --camera overrides the program's view.
        cam, _ = camera_of(binary, os.path.join(LOOP, name), work, ["--camera", "0,0,0,0,0,0,50"])
        if max(abs(a - b) for a, b in zip(cam["eye"], [0, 0, 50])) > TOL:
            fail(f"{name} --camera: eye {cam['eye']}, expected [0, 0, 50]")
        print(f"{name}: checked against the camera of $vpr {vpr}, $vpt {vpt}, $vpd {vpd}, and --camera")
    cam, said = camera_of(binary, os.path.join(LOOP, "no_view.scad"), work)
    if said:
        fail(f"no_view.scad: csgrt said {said!r}")
    if abs(math.dist(cam["eye"], cam["lookat"]) - 140) < 1e-6:
        fail("no_view.scad: OpenSCAD's default distance, as though $vp* were set")
    print("no_view.scad: checked for csgrt's framing, nothing said")


def check_one_camera(binary, work, fail):
    d = os.path.join(work, "slide")
    os.makedirs(d)
    code, said = run(binary, [os.path.join(LOOP, "slide.scad"), "--animate", "4", "--size", SIZE, "-q", "-O", d], work)
    if code != 0:
        return fail(f"slide.scad --animate 4: exit {code}: {said}")
    cube = "cube(size = [10, 10, 10], center = false);\n"
    ball = "multmatrix([[1, 0, 0, {x}], [0, 1, 0, -8], [0, 0, 1, 0], [0, 0, 0, 1]]) {{\n\tsphere(r = 3);\n}}\n"
    whole = os.path.join(d, "whole.csg")
    with open(whole, "w") as f:
        f.write(cube + ball.format(x=0) + ball.format(x=30))
    cam, _ = camera_of(binary, whole, d)
    vec = lambda v: "[" + ", ".join(repr(x) for x in v) + "]"
    fixed = f"camera(eye = {vec(cam['eye'])}, lookat = {vec(cam['lookat'])}, up = {vec(cam['up'])}, fov = {cam['fov']!r});\n"
    for i in range(4):
        csg = os.path.join(d, f"hand{i}.csg")
        with open(csg, "w") as f:
            f.write(fixed + cube + ball.format(x=10 * i))
        code, said = run(binary, [csg, "--size", SIZE, "-q", "-o", f"hand{i}.png"], d)
        if code != 0:
            return fail(f"hand{i}.csg: exit {code}: {said}")
        if read(os.path.join(d, f"hand{i}.png")) != read(os.path.join(d, f"slide{i:05}.png")):
            fail(f"slide.scad frame {i} is not seen by the camera framing all the frames")
    print("slide.scad: checked, 4 frames against the one camera that frames them all")


def check_example(binary, work, fail):
    src = os.path.join(EXAMPLES, "Advanced", "animation.scad")
    d = os.path.join(work, "example")
    os.makedirs(d)
    code, said = run(binary, [src, "--animate", "8", "--size", SIZE, "-q", "-O", d], work)
    if code != 0:
        return fail(f"animation.scad --animate 8: exit {code}: {said}")
    frames = [read(os.path.join(d, f"animation{i:05}.png")) for i in range(8)]
    if len(set(frames)) != 8:
        fail(f"animation.scad: {len(set(frames))} different frames of 8")
    print("examples/Advanced/animation.scad: checked for 8 different frames")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    a = ap.parse_args()
    if shutil.which("openscad") is None:
        sys.exit("openscad is not on PATH (Debian: apt-get install -y openscad)")
    binary = os.path.abspath(a.csgrt)
    failed = []

    def fail(msg):
        print(f"FAIL {msg}")
        failed.append(msg)

    with tempfile.TemporaryDirectory() as work:
        check_turn(binary, work, fail)
        check_views(binary, work, fail)
        check_one_camera(binary, work, fail)
        check_example(binary, work, fail)
    print(f"{len(failed)} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
