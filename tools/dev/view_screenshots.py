#!/usr/bin/env python3
"""The README's pictures of `csgrt view`, taken from the window itself.

    python -m tools.dev.view_screenshots [--csgrt BIN] [--out docs]

Opens models/turned.scad (copied to a temporary folder) in `csgrt view
--size 640x400` on a virtual X display (Xvfb), and reads the window back
with ImageMagick's `import`: view.png once the first view is refined;
view_moving.png during a left drag (the reduced picture a moving view
shows); view_error.png after a broken save (its message over the last
picture). Needs Xvfb, xdotool, ImageMagick and OpenSCAD.
"""

import argparse
import os
import shutil
import subprocess
import tempfile
import time

from tools import ROOT
from tools.bench.view import xvfb

SIZE = "640x400"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    p.add_argument("--out", default=os.path.join(ROOT, "docs"))
    a = p.parse_args()
    server, display = xvfb()
    env = dict(os.environ, DISPLAY=display)
    env.pop("WAYLAND_DISPLAY", None)
    tmp = tempfile.mkdtemp()
    try:
        model = os.path.join(tmp, "turned.scad")
        shutil.copy(os.path.join(ROOT, "models", "turned.scad"), model)
        log = open(os.path.join(tmp, "log.txt"), "w")
        viewer = subprocess.Popen([a.csgrt, "view", "turned.scad", "--size", SIZE, "--log-frames"], cwd=tmp,
                                  env=env, stdout=subprocess.DEVNULL, stderr=log)
        try:
            xdo = lambda *args: subprocess.run(["xdotool", *args], env=env, capture_output=True, text=True,
                                               timeout=60).stdout.strip()
            wid = xdo("search", "--sync", "--name", "^csgrt view").split()[0]
            title = lambda: xdo("getwindowname", wid)

            def until(ok, what):
                t0 = time.time()
                while not ok():
                    if time.time() - t0 > 60:
                        raise SystemExit(f"gave up waiting for {what}")
                    time.sleep(0.1)

            def shot(name):
                subprocess.run(["import", "-window", wid, os.path.join(a.out, name)], env=env, check=True)
                print(os.path.join(a.out, name))

            until(lambda: title().endswith("ready"), "the first picture")
            # A drag of 2 s going on while the window is read.
            chain = ["xdotool", "mousemove", "--window", wid, "320", "200", "mousedown", "1"]
            for i in range(1, 120):
                chain += ["mousemove", "--window", wid, str(320 - i), str(200 + i // 4), "sleep", "0.016"]
            drag = subprocess.Popen(chain + ["mouseup", "1"], env=env)
            time.sleep(1.0)
            shot("view_moving.png")
            drag.wait()
            until(lambda: title().endswith("ready"), "the refined picture")
            shot("view.png")
            with open(model) as f:
                text = f.read()
            with open(model + ".tmp", "w") as f:
                f.write(text.replace("r = 2);", "r = 2;", 1))
            os.replace(model + ".tmp", model)
            until(lambda: "error" in title(), "the broken save's message")
            time.sleep(0.3)
            shot("view_error.png")
        finally:
            viewer.kill()
            viewer.wait()
    finally:
        server.kill()
        server.wait()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
