#!/usr/bin/env python3
"""How many of a folder's OpenSCAD models csgrt renders, and why the others stop.

    tools/dev/survey.py [--csgrt target/release/csgrt] [--out DIR] FOLDER...

Each `.scad` under the folders is exported by OpenSCAD (`openscad -o x.csg`,
60 s at most); a file that exports nothing (a library of modules, an error
of its own, a missing include) is not a model and is counted apart. The
export is written beside the model (`x.scad.survey.csg`). Every
exported model is rendered by csgrt at 160×120, one sample; csgrt's first
error line, with file names and positions taken out, is its reason. Prints
the counts and the reasons, most frequent first; `--json` writes them.

Needs `openscad` (Debian `openscad`) on PATH. The models are not part of
csgrt: point it at any folder of people's models (docs/DETAILS.md says which
public repositories the last survey used).
"""

import argparse
import collections
import concurrent.futures
import json
import os
import random
import re
import subprocess
import sys
import tempfile


def export(scad, out):
    """OpenSCAD's export of `scad` to `out`: None when it made a model, else why not."""
    try:
        p = subprocess.run(
            ["openscad", "-o", out, scad],
            cwd=os.path.dirname(scad) or ".",
            capture_output=True,
            text=True,
            timeout=60,
        )
    except subprocess.TimeoutExpired:
        return "openscad: over 60 s"
    if p.returncode != 0 or not os.path.exists(out):
        return "openscad: failed"
    if "Current top level object is empty" in p.stderr:
        return "openscad: empty (a library)"
    return kept(out)


def kept(csg):
    """None for an export with a solid or a shape in it, else why not."""
    with open(csg) as f:
        text = f.read()
    if not re.search(r"\w+\s*\(", text.replace("group()", "")):
        return "openscad: empty (a library)"
    return None


def reason(stderr):
    """csgrt's first error line without file names, positions and numbers."""
    for line in stderr.splitlines():
        line = line.strip()
        if line.startswith("error") or ": error" in line:
            line = re.sub(r"^.*?error(\[[^\]]*\])?:\s*", "", line)
            line = re.sub(r"`[^`]*\.(csg|scad|stl|off|dxf|svg)`", "FILE", line)
            line = re.sub(r"\d+(\.\d+)?", "N", line)
            return line[:160]
    tail = stderr.strip().splitlines()
    return (tail[-1] if tail else "no message")[:160]


def survey(scad, csgrt, out_dir, reuse=False):
    base = re.sub(r"[^A-Za-z0-9]+", "_", scad)[-120:]
    # Beside the model, so that the export's relative imports still resolve.
    csg = scad + ".survey.csg"
    why = kept(csg) if reuse and os.path.exists(csg) else export(scad, csg)
    if why:
        return scad, "skipped", why
    png = os.path.join(out_dir, base + ".png")
    try:
        p = subprocess.run(
            [csgrt, "-q", "--size", "160x120", "--spp", "1", "--threads", "1", "-o", png, csg],
            capture_output=True,
            text=True,
            timeout=300,
        )
    except subprocess.TimeoutExpired:
        return scad, "failed", "csgrt: over 300 s"
    if p.returncode == 0:
        return scad, "rendered", ""
    if "No such file or directory" in p.stderr:
        # A drawing, mesh or image the model imports that is not in the
        # copy surveyed (a large file a snapshot leaves out, one a build
        # script makes): not the model as its author has it.
        return scad, "missing", reason(p.stderr)
    if p.returncode not in (1, 2):
        return scad, "failed", f"csgrt crashed (exit {p.returncode})"
    return scad, "failed", reason(p.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--csgrt", default="target/release/csgrt")
    ap.add_argument("--out", help="keep the exports and images here")
    ap.add_argument("--json", help="write every model's outcome here")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument(
        "--reuse",
        action="store_true",
        help="render the exports an earlier run left beside the models (x.scad.survey.csg) "
        "instead of exporting again (to compare two builds of csgrt on the same files)",
    )
    ap.add_argument(
        "--per-folder",
        type=int,
        help="at most this many files of each folder given, a fixed sample (one project's "
        "shared module would otherwise count once for each of its parts)",
    )
    a = ap.parse_args()
    csgrt = os.path.abspath(a.csgrt)
    scads = []
    for folder in a.folders:
        found = sorted(
            os.path.abspath(os.path.join(d, f))
            for d, _, fs in os.walk(folder)
            for f in fs
            if f.endswith(".scad")
        )
        if a.per_folder and len(found) > a.per_folder:
            found = random.Random(0).sample(found, a.per_folder)
        scads += found
    out_dir = a.out or tempfile.mkdtemp(prefix="survey")
    os.makedirs(out_dir, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as ex:
        rows = list(ex.map(lambda s: survey(s, csgrt, out_dir, a.reuse), scads))
    kinds = collections.Counter(r[1] for r in rows)
    models = kinds["rendered"] + kinds["failed"]
    print(
        f"{len(rows)} files: {models} models, {kinds['skipped']} not models, "
        f"{kinds['missing']} missing a file they import"
    )
    if models:
        print(f"rendered {kinds['rendered']} of {models} ({100 * kinds['rendered'] / models:.0f} %)")
    for why, n in collections.Counter(r[2] for r in rows if r[1] == "failed").most_common():
        print(f"{n:5}  {why}")
    for why, n in collections.Counter(r[2] for r in rows if r[1] == "skipped").most_common():
        print(f"{n:5}  (not a model) {why}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{"file": s, "outcome": k, "reason": w} for s, k, w in rows], f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
