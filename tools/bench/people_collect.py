#!/usr/bin/env python3
"""Gathers the bench of people's models (bench/people/): OpenSCAD's exports of
a fixed sample of each licensed repository's models, with the files they
import and the repository's licence.

    python -m tools.bench.people_collect [--per-repo 14] [--out bench/people] GITDIR...

Each GITDIR is a snapshot's git directory named `.../owner+name/repo` (what
the tool library's `fetch` leaves in /work/.mirror). Its HEAD's files are
written out (blobs a snapshot lacks are left out), its `.scad` files are
shuffled with a fixed seed and exported by OpenSCAD as the survey exports
(`tools/dev/survey.py`'s `export`: `openscad -o x.csg`, 60 s at most, not
empty) until `--per-repo` of them made a model: such an export of at most
2 MB, every file it imports present and at most 2 MB.
The export goes to OUT/owner+name/<the model's path>.csg (the imports
beside it at their own relative paths, so that the export reads them as
OpenSCAD did), the licence to OUT/owner+name/LICENSE*, and one line a model
to OUT/SOURCES.md (repository, commit, path, licence).

Which repositories: those of the survey (docs/DETAILS.md, "People's models") whose
snapshot carries a licence that lets a copy be kept here.
"""

import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

from tools.dev.survey import export

MAX_BYTES = 2 << 20
# A licence stated in the README only: the repository's own words, kept with
# the models as its licence.
README_LICENCES = {
    "CarlosGS+Cyclone-PCB-Factory": "CC BY-SA 3.0 (README.md: \"License: Attribution - Share "
    "Alike - Creative Commons (http://creativecommons.org/licenses/by-sa/3.0/)\")",
}


def git(gitdir, *args):
    return subprocess.run(["git", "-C", gitdir, *args], capture_output=True, check=True).stdout


def write_tree(gitdir, into):
    """HEAD's files under `into`; blobs the snapshot lacks are left out."""
    for e in git(gitdir, "ls-tree", "-r", "-z", "HEAD").split(b"\0"):
        if not e:
            continue
        meta, path = e.split(b"\t", 1)
        mode, kind, sha = meta.split()
        if kind != b"blob" or mode == b"120000":
            continue
        p = subprocess.run(["git", "-C", gitdir, "cat-file", "blob", sha], capture_output=True)
        if p.returncode:
            continue
        out = os.path.join(into, path.decode(errors="replace"))
        os.makedirs(os.path.dirname(out), exist_ok=True)
        with open(out, "wb") as f:
            f.write(p.stdout)


def licence(tree):
    """(file name, first words) of the repository's licence file, or None."""
    for name in sorted(os.listdir(tree)):
        if re.match(r"(?i)^(licen[cs]e|copying)", name) and os.path.isfile(os.path.join(tree, name)):
            with open(os.path.join(tree, name), errors="replace") as f:
                words = " ".join(f.read().split()[:8])
            return name, words
    return None


def imports(csg_text):
    return re.findall(r'\bfile\s*=\s*"((?:[^"\\]|\\.)*)"', csg_text)


def collect(gitdir, per_repo, out, lines):
    name = os.path.basename(os.path.dirname(os.path.abspath(gitdir)))
    commit = git(gitdir, "rev-parse", "HEAD").decode().strip()
    with tempfile.TemporaryDirectory(prefix="people") as tree:
        write_tree(gitdir, tree)
        lic = licence(tree)
        if lic is None and name not in README_LICENCES:
            print(f"{name}: no licence, left out", file=sys.stderr)
            return
        scads = sorted(
            os.path.relpath(os.path.join(d, f), tree)
            for d, _, fs in os.walk(tree)
            for f in fs
            if f.endswith(".scad")
        )
        random.Random(0).shuffle(scads)
        dest = os.path.join(out, name)
        if lic:
            os.makedirs(dest, exist_ok=True)
            shutil.copy(os.path.join(tree, lic[0]), os.path.join(dest, lic[0]))
            words = lic[1]
        else:
            words = README_LICENCES[name]
            os.makedirs(dest, exist_ok=True)
            with open(os.path.join(dest, "LICENSE.txt"), "w") as f:
                f.write(f"The repository {name.replace('+', '/')} states its licence as {words}.\n")
        kept = 0
        for rel in scads:
            if kept == per_repo:
                break
            scad = os.path.join(tree, rel)
            csg = scad + ".csg"
            if export(scad, csg) or os.path.getsize(csg) > MAX_BYTES:
                continue
            with open(csg, errors="replace") as f:
                text = f.read()
            files = [os.path.normpath(os.path.join(os.path.dirname(rel), i)) for i in imports(text) if i]
            if any(
                os.path.isabs(i) or i.startswith("..") or not os.path.isfile(os.path.join(tree, i))
                or os.path.getsize(os.path.join(tree, i)) > MAX_BYTES
                for i in files
            ):
                continue
            for i in files + [rel + ".csg"]:
                os.makedirs(os.path.dirname(os.path.join(dest, i)), exist_ok=True)
                shutil.copy(os.path.join(tree, i), os.path.join(dest, i))
            lines.append(f"| {name.replace('+', '/')} | `{commit[:12]}` | `{rel}` | {words} |")
            kept += 1
        print(f"{name}: {kept} models", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gitdirs", nargs="+")
    ap.add_argument("--per-repo", type=int, default=14)
    ap.add_argument("--out", default="bench/people")
    a = ap.parse_args()
    lines = []
    for g in a.gitdirs:
        collect(g, a.per_repo, a.out, lines)
    with open(os.path.join(a.out, "SOURCES.md"), "w") as f:
        f.write(
            "# Sources of bench/people\n\n"
            "OpenSCAD 2021.01's exports (`openscad -o x.csg x.scad`) of people's models, gathered by\n"
            "`tools/bench/people_collect.py`; each folder holds its repository's licence. Each model is\n"
            "its author's work under that licence; the exports are kept here unchanged, to be timed.\n\n"
            "| repository | commit | model | licence |\n|---|---|---|---|\n"
        )
        f.write("\n".join(lines) + "\n")
    print(f"{len(lines)} models", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
