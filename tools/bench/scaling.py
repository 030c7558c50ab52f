#!/usr/bin/env python3
"""csgrt's speed-up with threads, on a machine with nothing else running.

Renders each scene of the bench set (models/*.csg and bench/*.csg, or the
scenes named) with csgrt at each thread count of --threads, the counts
alternating within each of --rounds rounds so that a drift of the
machine's speed falls on all of them alike, and writes a Markdown table:
the median `render_seconds` (--stats-json) at each count, and each count's
speed-up over one thread both from those medians and as the median of each
round's own ratio. No peer is needed: this is the measure for a machine
without POV-Ray (`tools/bench/bench.py` times csgrt against POV-Ray, and on a
shared machine its all-core figure drifts with whatever else runs).

With --ceiling each round also starts as many one-thread renders at once
as the largest count and gives the machine's own ceiling for that count:
the count times one render's time alone over each render's time when they
run together (median of the rounds' ratios). Independent processes share
nothing but the machine, so a speed-up near the ceiling is all the
machine allows; on a virtual machine whose cores share their caches or
their physical core it can be well under the count.

Usage: scaling.py [--csgrt BIN] [--size WxH] [--rounds N] [--threads 1,2,0]
                  [--ceiling] [--out FILE] [SCENE...]  (a count of 0: every core)
"""

import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile


def render_seconds(csgrt, scene, size, threads, tmp, copies=1):
    """The render time of one render on `threads` threads; with `copies`
    above one, that many one-thread renders started together and the
    median of their times."""
    procs, files = [], []
    for k in range(copies):
        png = os.path.join(tmp, f"out{k}.png")
        stats = os.path.join(tmp, f"stats{k}.json")
        procs.append(subprocess.Popen(
            [csgrt, scene, "--size", size, "--spp", "1", "--threads", str(threads), "-q",
             "-o", png, "--stats-json", stats],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE))
        files.append(stats)
    for p in procs:
        # communicate, not wait: a child whose stderr filled the pipe would
        # never end.
        _, err = p.communicate()
        if p.returncode != 0:
            sys.exit(f"scaling.py: csgrt failed on {scene}: {err.decode()}")
    times = []
    for stats in files:
        with open(stats) as f:
            times.append(json.load(f)["render_seconds"])
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--csgrt", default="target/release/csgrt")
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--threads", default="1,2,0")
    ap.add_argument("--out", default=None)
    ap.add_argument("--ceiling", action="store_true",
                    help="also run as many one-thread renders at once as the largest count: "
                         "the machine's own ceiling for that count (count x one alone / each at once)")
    a = ap.parse_args()
    cores = os.cpu_count() or 1
    counts = []
    for x in a.threads.split(","):
        n = int(x) or cores
        if n not in counts:
            counts.append(n)
    if counts[0] != 1:
        sys.exit("scaling.py: the first thread count must be 1 (the speed-ups are over it)")
    scenes = a.scenes or sorted(glob.glob("models/*.csg")) + sorted(glob.glob("bench/*.csg"))
    head = ["scene"] + [f"{n} thread{'s' if n > 1 else ''}" for n in counts]
    for n in counts[1:]:
        head += [f"speed-up on {n} (medians)", "(paired rounds)"]
    top = counts[-1]
    if a.ceiling and top > 1:
        head += [f"{top} one-thread renders at once: ceiling (paired rounds)"]
    rows = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            times = {n: [] for n in counts}
            together = []
            for _ in range(a.rounds):
                for n in counts:
                    times[n].append(render_seconds(a.csgrt, scene, a.size, n, tmp))
                if a.ceiling and top > 1:
                    together.append(render_seconds(a.csgrt, scene, a.size, 1, tmp, copies=top))
            med = {n: statistics.median(v) for n, v in times.items()}
            cells = [os.path.splitext(os.path.basename(scene))[0]]
            cells += [f"{med[n]:.4f} s" for n in counts]
            for n in counts[1:]:
                paired = statistics.median(t1 / tn for t1, tn in zip(times[1], times[n]))
                cells += [f"{med[1] / med[n]:.2f}×", f"{paired:.2f}×"]
            if together:
                ceiling = statistics.median(top * t1 / tt for t1, tt in zip(times[1], together))
                cells += [f"{ceiling:.2f}×"]
            rows.append("| " + " | ".join(cells) + " |")
            print(rows[-1], flush=True)
    text = (f"csgrt {a.size}, one sample a pixel, median of {a.rounds} rounds, "
            f"{cores} cores seen by the process.\n\n" + "\n".join(rows) + "\n")
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
