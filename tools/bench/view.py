#!/usr/bin/env python3
"""Interaction with `csgrt view` (issue 47): views shown a second while orbiting,
time from release to the final picture, time from a save to its picture.

    python -m tools.bench.view [--csgrt BIN] [--people N] [--seconds 3] [--out F] [--json F] [FILE...]

Each model (the bench scenes, bench/*.csg, and N of the people's models, every
k-th by name, unless files are given) is opened in `csgrt view --size 800x600
--log-frames` on a virtual X display of its own (Debian's Xvfb; `xdotool`
drives the mouse), on this machine's cores:

* open: from the process's start to its first final (anti-aliased) picture;
* orbiting: the left button held and the mouse moved 2 pixels every 1/60 s
  (1.4° a step, OpenSCAD's 0.7° a pixel) for --seconds; the views the
  window shows a picture of in that time (of any pass: reduced, full,
  final), a second, counted from 0.25 s after the drag begins — at most the
  60 views a second the mouse asks for; and the reduction the viewer chose
  (1/n: each picture pixel stands for n×n of the window's);
* release: from the last view asked (the last mouse move) to its first
  full-resolution picture (anti-aliasing's first pass), and to its final one;
* save: the model written again (a new file renamed over it, as editors
  save), from that moment to the final picture of the model read again —
  the watch's 100 ms of quiet and the reading included.

Times come from the viewer's `--log-frames` lines, whose clock the first
line ties to the epoch. Needs Xvfb and xdotool (`apt-get install -y xvfb
xdotool`).
"""

import argparse
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from tools import ROOT

SIZE = "800x600"
STEP_PX = 2
STEP_S = 1 / 60
LINE = re.compile(r"^csgrt view: ([\d.]+) s: (.*)$")
PICTURE = re.compile(r"^view (\d+) (reduced 1/(\d+)|full|final) (\d+)x(\d+) in ([\d.]+) s$")


def xvfb():
    for n in range(200 + os.getpid() % 300, 1000):
        if os.path.exists(f"/tmp/.X{n}-lock") or os.path.exists(f"/tmp/.X11-unix/X{n}"):
            continue
        p = subprocess.Popen(["Xvfb", f":{n}", "-screen", "0", "1024x768x24", "-nolisten", "tcp"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for _ in range(200):
            if os.path.exists(f"/tmp/.X11-unix/X{n}"):
                return p, f":{n}"
            time.sleep(0.05)
        p.kill()
    raise SystemExit("no X display could be started")


def parse(log):
    began, events = None, []
    for line in log.splitlines():
        m = re.match(r"^csgrt view: began at ([\d.]+) s after 1970$", line)
        if m:
            began = float(m.group(1))
            continue
        m = LINE.match(line)
        if m:
            events.append((float(m.group(1)), m.group(2)))
    return began, events


def pictures(events):
    out = []
    for t, what in events:
        m = PICTURE.match(what)
        if m:
            out.append({"t": t, "view": int(m.group(1)), "pass": m.group(2).split(" ")[0],
                        "n": int(m.group(3) or 1), "seconds": float(m.group(6))})
    return out


def wait_for(path, ok, limit):
    t0 = time.time()
    while time.time() - t0 < limit:
        text = open(path).read() if os.path.exists(path) else ""
        if ok(text):
            return text
        time.sleep(0.05)
    return None


def finals_of(text, view):
    return [p for p in pictures(parse(text)[1]) if p["view"] == view and p["pass"] == "final"]


def last_asked(text):
    asked = [int(w.split()[-1]) for _, w in parse(text)[1] if w.startswith("asked view")]
    return asked[-1] if asked else None


def measure(binary, model, display, seconds, limit):
    tmp = tempfile.mkdtemp()
    try:
        local = os.path.join(tmp, os.path.basename(model))
        shutil.copy(model, local)
        log = os.path.join(tmp, "log.txt")
        env = dict(os.environ, DISPLAY=display)
        env.pop("WAYLAND_DISPLAY", None)
        t_start = time.time()
        with open(log, "w") as err:
            proc = subprocess.Popen([binary, "view", os.path.basename(local), "--size", SIZE, "--log-frames",
                                     "-q"], cwd=tmp, env=env, stdout=subprocess.DEVNULL, stderr=err)
        try:
            text = wait_for(log, lambda s: finals_of(s, 1), limit)
            if text is None:
                return {"model": model, "why": f"no first picture in {limit} s"}
            began, _ = parse(text)
            open_s = began + finals_of(text, 1)[0]["t"] - t_start
            wid = subprocess.run(["xdotool", "search", "--sync", "--name", "^csgrt view"], env=env,
                                 capture_output=True, text=True, timeout=30).stdout.split()[0]
            steps = int(seconds / STEP_S)
            chain = ["xdotool", "mousemove", "--window", wid, "200", "300", "mousedown", "1"]
            for i in range(1, steps + 1):
                chain += ["mousemove", "--window", wid, str(200 + STEP_PX * (i % 150)), "300",
                          "sleep", f"{STEP_S:.4f}"]
            chain += ["mouseup", "1"]
            d0 = time.time()
            subprocess.run(chain, env=env, timeout=seconds * 4 + 30)
            d1 = time.time()
            text = wait_for(log, lambda s: last_asked(s) and finals_of(s, last_asked(s)), limit)
            if text is None:
                return {"model": model, "why": f"no final picture {limit} s after release"}
            began, events = parse(text)
            last = last_asked(text)
            asked_t = max(t for t, w in events if w == f"asked view {last}")
            release_s = finals_of(text, last)[0]["t"] - asked_t
            full_t = min(p["t"] for p in pictures(events) if p["view"] == last and p["pass"] in ("full", "final"))
            release_full_s = full_t - asked_t
            lo, hi = d0 - began + 0.25, d1 - began
            shown = [p for p in pictures(events) if lo <= p["t"] <= hi]
            fps = len({p["view"] for p in shown}) / (hi - lo)
            reductions = [p["n"] for p in shown if p["pass"] == "reduced"]
            # A save: the same text, a new file renamed over the model.
            with open(local) as f:
                body = f.read()
            before = len(events)
            t_save = time.time()
            with open(local + ".tmp~", "w") as f:
                f.write(body)
            os.replace(local + ".tmp~", local)

            def saved_final(s):
                ev = parse(s)[1][before:]
                read = [t for t, w in ev if w == "read"]
                if not read:
                    return False
                later = [p for p in pictures(ev) if p["pass"] == "final" and p["t"] >= read[0]]
                return bool(later)

            text = wait_for(log, saved_final, limit)
            save_s = None
            if text is not None:
                began, events = parse(text)
                ev = events[before:]
                read_t = [t for t, w in ev if w == "read"][0]
                final_t = [p["t"] for p in pictures(ev) if p["pass"] == "final" and p["t"] >= read_t][0]
                save_s = began + final_t - t_save
            return {"model": model, "open": open_s, "fps": fps, "pictures": len(shown),
                    "reduction": statistics.median(reductions) if reductions else 1,
                    "reduced_seconds": statistics.median([p["seconds"] for p in shown if p["pass"] == "reduced"])
                    if reductions else None,
                    "release": release_s, "release_full": release_full_s, "save": save_s}
        finally:
            proc.kill()
            proc.wait()
            if os.environ.get("VIEW_KEEP_LOG"):
                shutil.copy(log, os.environ["VIEW_KEEP_LOG"])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    p.add_argument("--people", type=int, default=12, help="how many of the people's models (every k-th by name)")
    p.add_argument("--seconds", type=float, default=3.0)
    p.add_argument("--limit", type=float, default=120.0)
    p.add_argument("--out")
    p.add_argument("--json")
    p.add_argument("files", nargs="*")
    a = p.parse_args()
    for tool in ("Xvfb", "xdotool"):
        if shutil.which(tool) is None:
            raise SystemExit(f"{tool} is not installed (apt-get install -y xvfb xdotool)")
    files = a.files
    if not files:
        files = sorted(glob.glob(os.path.join(ROOT, "bench", "*.csg")))
        people = sorted(glob.glob(os.path.join(ROOT, "bench", "people", "**", "*.csg"), recursive=True))
        if a.people and people:
            k = max(1, len(people) // a.people)
            files += people[::k][: a.people]
    server, display = xvfb()
    rows = []
    try:
        for f in files:
            r = measure(a.csgrt, f, display, a.seconds, a.limit)
            rows.append(r)
            name = os.path.relpath(f, ROOT)
            if "why" in r:
                print(f"{name}: {r['why']}", file=sys.stderr)
            else:
                print(f"{name}: open {r['open']:.3f} s, {r['fps']:.1f} views/s orbiting (1/{r['reduction']:g}), "
                      f"release {r['release']:.3f} s, save {r['save'] if r['save'] is None else round(r['save'], 3)} s",
                      file=sys.stderr)
    finally:
        server.kill()
        server.wait()
    ok = [r for r in rows if "why" not in r]
    fmt = lambda v: "—" if v is None else f"{v:.3f}"
    head = ("| model | open: first final picture (s) | views shown a second while orbiting | reduction "
            "| reduced picture (s) | release → full resolution (s) | release → final (s) | save → final (s) |\n"
            "|---|---|---|---|---|---|---|---|\n")
    body = "".join(
        f"| {os.path.relpath(r['model'], ROOT)} | {fmt(r['open'])} | {r['fps']:.1f} | 1/{r['reduction']:g} | "
        f"{fmt(r['reduced_seconds'])} | {fmt(r['release_full'])} | {fmt(r['release'])} | {fmt(r['save'])} |\n"
        for r in ok)
    fails = "".join(f"| {os.path.relpath(r['model'], ROOT)} | {r['why']} | | | | | | |\n" for r in rows if "why" in r)
    summary = ""
    if ok:
        fps = sorted(r["fps"] for r in ok)
        summary = (f"\n{len(ok)} models: views shown a second while orbiting median {statistics.median(fps):.1f}, "
                   f"lowest {fps[0]:.1f}; {sum(f >= 30 for f in fps)} of {len(ok)} at 30 or more; release → full resolution "
                   f"median {statistics.median(r['release_full'] for r in ok):.3f} s; release → final "
                   f"median {statistics.median(r['release'] for r in ok):.3f} s; save → final median "
                   f"{statistics.median(r['save'] for r in ok if r['save'] is not None):.3f} s.\n")
    text = head + body + fails + summary
    sys.stdout.write(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
