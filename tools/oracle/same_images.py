#!/usr/bin/env python3
"""Has a change left every picture and every counter as it was?

Renders every model, test scene, OpenSCAD export and bench scene at 160x120
with 2 samples a pixel, and hashes the PNG's bytes and the `--stats-json`
counters (all but `render_seconds`). `--write` records the hashes in
tests/same_images.txt; `--check` (in .ci/run) compares with that file and
names every scene whose image or counters changed. A change that means to
alter pictures or counters (a fix, a faster walk that tests fewer boxes)
rewrites the file in the same commit and says why in its message.

Usage: same_images.py [--csgrt BIN] (--check | --write) [--file FILE]
"""

import argparse
import glob
import hashlib
import json
import os
import subprocess
import sys
import tempfile

from tools import ROOT
PATTERNS = ["models/*.csg", "models/*.ray", "tests/scenes/*.csg", "tests/openscad/*.csg", "bench/*.csg"]


def scenes():
    out = []
    for p in PATTERNS:
        out += sorted(glob.glob(os.path.join(ROOT, p)))
    return out


def fingerprint(binary, path, work):
    image, stats = os.path.join(work, "i.png"), os.path.join(work, "s.json")
    subprocess.run(
        [binary, path, "--size", "160x120", "--spp", "2", "--threads", "2", "-o", image, "--stats-json", stats, "-q"],
        check=True,
    )
    with open(image, "rb") as f:
        img = hashlib.sha256(f.read()).hexdigest()[:16]
    with open(stats) as f:
        counters = json.load(f)
    counters.pop("render_seconds", None)
    cnt = hashlib.sha256(json.dumps(counters, sort_keys=True).encode()).hexdigest()[:16]
    return img, cnt, counters


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target/release/csgrt"))
    ap.add_argument("--file", default=os.path.join(ROOT, "tests/same_images.txt"))
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--check", action="store_true")
    g.add_argument("--write", action="store_true")
    a = ap.parse_args()
    rows = {}
    with tempfile.TemporaryDirectory() as work:
        for path in scenes():
            rel = os.path.relpath(path, ROOT)
            rows[rel] = fingerprint(a.csgrt, path, work)
    if a.write:
        with open(a.file, "w") as f:
            f.write("# scene, sha256 of the PNG (160x120, --spp 2), sha256 of the counters; tools/oracle/same_images.py\n")
            for rel, (img, cnt, _) in rows.items():
                f.write(f"{rel} {img} {cnt}\n")
        print(f"{len(rows)} scenes written to {os.path.relpath(a.file, ROOT)}")
        return
    want = {}
    with open(a.file) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            rel, img, cnt = line.split()
            want[rel] = (img, cnt)
    bad = 0
    for rel in sorted(set(want) | set(rows)):
        if rel not in rows:
            print(f"FAIL {rel}: recorded but no longer there")
        elif rel not in want:
            print(f"FAIL {rel}: not recorded (run --write)")
        else:
            img, cnt, counters = rows[rel]
            what = [w for w, same in (("image", img == want[rel][0]), ("counters", cnt == want[rel][1])) if not same]
            if not what:
                continue
            print(f"FAIL {rel}: the {' and the '.join(what)} changed (counters now {json.dumps(counters, sort_keys=True)})")
        bad += 1
    print(f"{len(rows) - bad} passed, {bad} failed")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
