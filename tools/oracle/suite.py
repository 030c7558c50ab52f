#!/usr/bin/env python3
"""OpenSCAD 2021.01's own regression suite as the judge of csgrt's pictures.

    python -m tools.oracle.suite [--csgrt BIN] [--only TEXT,...] [--report FILE]
    python -m tools.oracle.suite --vendor CHECKOUT

tests/openscad_suite/ holds, from OpenSCAD's repository at tag
openscad-2021.01 (GPL-2.0: its COPYING and README there), OpenSCAD's own
exports (`openscad -o x.csg x.scad`) of the testdata/scad models that it
renders to a solid or a shape and that its suite has an expected image for,
the data files they import, at the same places, and those expected images
(tests/regression/cgalpngtest, the --render ones; opencsgtest where there is
none). `--vendor CHECKOUT` writes that folder again from a checkout of the
tag (`git archive openscad-2021.01 testdata tests/regression | tar -x`) with
the `openscad` on PATH; nothing in it is csgrt's.

The check renders every vendored model at the suite's own camera and size
(512 x 512; files under 2D/, dxf/ and svg/ with `--camera=0,0,100,0,0,0
--viewall --autocenter --projection=ortho`, the others with `--viewall
--autocenter`, as tests/CMakeLists.txt runs them) and compares csgrt's hit
mask (`--mask`) with the expected image's silhouette (every pixel that is not
the Cornfield background, 255 255 229). A pixel disagrees when the two
differ there and neither has an edge within EDGE pixels of it (each image is
all one value over the (2 EDGE + 1)^2 square around it): faceting, OpenSCAD's
drawn edges and anti-aliasing stay within that band. A file with more than
ALLOWED disagreeing pixels fails, unless tests/openscad_suite/by_design.txt
lists it with its class and reason; for a listed file the reason is checked
where it can be (`facets`: the file agrees with `--facets openscad`;
`refused`: csgrt refuses it), and a listed file that agrees, or whose reason
no longer holds, fails too (the table must stay true).

Prints one line per file that is not a plain pass, then the counts: files,
rendered, agreeing, disagreeing, by design (by class). Exit status 1 on any
failure.
"""

import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from tools import ROOT

SUITE = os.path.join(ROOT, "tests", "openscad_suite")
SIZE = 512
EDGE = 2
ALLOWED = 0
BACKGROUND = (255, 255, 229)
TWO_D = ("2D/", "dxf/", "svg/")
CAMERA_2D = ["--camera=0,0,100,0,0,0", "--viewall", "--autocenter", "--projection=ortho"]
CAMERA_3D = ["--viewall", "--autocenter"]
TIMEOUT = 120
# Where csgrt does not build OpenSCAD's facets, a `facets` file's blobs must
# lie within this many pixels of the edges.
FACET_EDGE = 6

# The classes of by_design.txt, and what is checked of each.
CLASSES = {
    "facets": "OpenSCAD's facets ($fn, $fa, $fs, slices) where csgrt is exact: the file agrees with --facets openscad, or, where csgrt does not build those facets, within FACET_EDGE pixels of the edges",
    "preview": "the suite's image is of OpenSCAD's preview (opencsgtest: % and # shown), there is no --render one: the image is from expected_preview/",
    "font": "text in a font the export does not carry (the suite loads its fonts with `use <x.ttf>`): the model has text()",
    "slab": "a 2-D model outside 2D/, dxf/ and svg/, seen from the 3-D camera: OpenSCAD's render draws it flat, csgrt as OpenSCAD's preview does (a slab 1 thick)",
    "openscad": "OpenSCAD's own result is wrong (a known OpenSCAD bug, named in the reason)",
    "export": "OpenSCAD's .csg export says something else than the model (the reason says what)",
    "limit": "csgrt's shortfall, to be fixed (the reason says what)",
    "refused": "csgrt refuses the model (see issue 44): csgrt still refuses it",
}


def models():
    """The vendored exports, as paths below testdata/scad."""
    top = os.path.join(SUITE, "testdata", "scad")
    out = []
    for d, _, fs in os.walk(top):
        out += [os.path.relpath(os.path.join(d, f), top) for f in fs if f.endswith(".csg")]
    return sorted(out)


def test_name(rel):
    """The suite's test name: the file's base name (spaces as _)."""
    return os.path.basename(rel)[: -len(".csg")].replace(" ", "_")


def camera(rel):
    return CAMERA_2D if rel.startswith(TWO_D) else CAMERA_3D


def by_design():
    """{file below testdata/scad: (class, reason)} from by_design.txt."""
    table = {}
    with open(os.path.join(SUITE, "by_design.txt")) as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            parts = line.split(None, 2)
            if len(parts) < 3:
                sys.exit(f"by_design.txt:{n}: expected FILE CLASS REASON")
            table[parts[0]] = (parts[1], parts[2])
    return table


def silhouette(path):
    """The expected image's object pixels: everything but the background."""
    a = np.asarray(Image.open(path).convert("RGB"), dtype=np.int16)
    return np.abs(a - np.array(BACKGROUND, dtype=np.int16)).max(axis=2) > 8


def settled(mask, edge):
    """Pixels whose (2 edge + 1)^2 square is all one value in `mask`."""
    h, w = mask.shape
    m = mask.astype(np.int16)
    p = np.pad(m, edge, mode="edge")
    lo, hi = m.copy(), m.copy()
    for dy in range(-edge, edge + 1):
        for dx in range(-edge, edge + 1):
            s = p[edge + dy : edge + dy + h, edge + dx : edge + dx + w]
            lo, hi = np.minimum(lo, s), np.maximum(hi, s)
    return lo == hi


def disagreement(expected, got, edge=None):
    """How many pixels disagree away from both images' edges (EDGE, or
    `edge` pixels)."""
    edge = EDGE if edge is None else edge
    return int(np.count_nonzero((expected != got) & settled(expected, edge) & settled(got, edge)))


def render(binary, rel, extra=()):
    """(csgrt's hit mask or None, its first error line)."""
    model = os.path.join(SUITE, "testdata", "scad", rel)
    with tempfile.TemporaryDirectory() as tmp:
        png, mask = os.path.join(tmp, "x.png"), os.path.join(tmp, "m.png")
        cmd = [binary, model, "-o", png, "--mask", mask, "--size", f"{SIZE}x{SIZE}", "--spp", "1", "-q", *camera(rel), *extra]
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            return None, f"over {TIMEOUT} s"
        if p.returncode != 0 or not os.path.exists(mask):
            lines = [x for x in p.stderr.splitlines() if "error" in x] or p.stderr.splitlines() or ["no message"]
            return None, lines[0][:200]
        # Under --facets openscad, what csgrt builds no facets of is drawn
        # exact with a warning: its facets are not built.
        exact = [x for x in p.stderr.splitlines() if "is drawn exact under `--facets openscad`" in x]
        if exact:
            return None, exact[0][:200]
        return np.asarray(Image.open(mask).convert("L")) > 127, ""


def expected_image(rel):
    """(the expected image's path, whether it is of OpenSCAD's preview:
    opencsgtest's, where the suite has no --render image)."""
    render = os.path.join(SUITE, "expected", test_name(rel) + ".png")
    if os.path.exists(render):
        return render, False
    return os.path.join(SUITE, "expected_preview", test_name(rel) + ".png"), True


def judge(job):
    """(file, verdict, detail): verdict one of pass, fail, by-design."""
    binary, rel, listed = job
    path, preview = expected_image(rel)
    expected = silhouette(path)
    got, why = render(binary, rel)
    if got is None:
        if listed and listed[0] == "refused":
            return rel, "refused", why
        return rel, "fail", f"csgrt does not render it: {why}"
    bad = disagreement(expected, got)
    if not listed:
        return rel, ("pass" if bad <= ALLOWED else "fail"), f"{bad} pixels disagree"
    if listed[0] not in CLASSES:
        return rel, "fail", f"by_design.txt: unknown class {listed[0]}"
    cls, reason = listed
    if bad <= ALLOWED:
        return rel, "fail", f"listed as {cls} but agrees ({bad} pixels): take it out of by_design.txt"
    if cls == "refused":
        return rel, "fail", "listed as refused but csgrt renders it"
    if cls == "facets":
        fine, why = render(binary, rel, ["--facets", "openscad"])
        if fine is not None:
            left = disagreement(expected, fine)
            if left > ALLOWED:
                return rel, "fail", f"listed as facets, but with --facets openscad {left} pixels still disagree"
            return rel, "by-design", f"facets: {bad} pixels, none with --facets openscad"
        left = disagreement(expected, got, FACET_EDGE)
        if left > ALLOWED:
            return rel, "fail", f"listed as facets, csgrt does not build them ({why}) and {left} pixels disagree beyond {FACET_EDGE} pixels of the edges"
        return rel, "by-design", f"facets: {bad} pixels, none beyond {FACET_EDGE} pixels of the edges"
    if cls == "preview" and not preview:
        return rel, "fail", "listed as preview, but its expected image is a --render one"
    if cls == "font" and "text(" not in open(os.path.join(SUITE, "testdata", "scad", rel)).read():
        return rel, "fail", "listed as font, but the model has no text()"
    if cls not in CLASSES:
        return rel, "fail", f"by_design.txt: unknown class {cls}"
    return rel, "by-design", f"{cls}: {bad} pixels ({reason})"


def check(binary, only, report):
    table = by_design()
    wanted = [x for x in only.split(",") if x]
    every = models()
    files = [r for r in every if not wanted or any(x in r for x in wanted)]
    for rel in table:
        if rel not in every:
            print(f"by_design.txt names {rel}, which is not in the suite")
            return 1
    jobs = [(binary, rel, table.get(rel)) for rel in files]
    results = []
    with concurrent.futures.ThreadPoolExecutor(max(1, os.cpu_count() or 1)) as ex:
        for rel, verdict, detail in ex.map(judge, jobs):
            results.append((rel, verdict, detail))
            if verdict in ("fail", "by-design"):
                print(f"{verdict:9} {rel}: {detail}", flush=True)
    counts = {v: sum(1 for _, x, _ in results if x == v) for v in ("pass", "fail", "by-design", "refused")}
    rendered = sum(1 for _, v, d in results if v != "refused" and not d.startswith("csgrt does not"))
    classes = {}
    for rel, v, _ in results:
        if v == "by-design":
            classes[table[rel][0]] = classes.get(table[rel][0], 0) + 1
    by_class = ", ".join(f"{k} {n}" for k, n in sorted(classes.items()))
    print(
        f"{len(results)} files, {rendered} rendered, {counts['pass']} agree, "
        f"{counts['fail']} fail, {counts['by-design']} in the table ({by_class or 'none'}), "
        f"{counts['refused']} refused (listed)"
    )
    if report:
        with open(report, "w") as f:
            for rel, v, d in results:
                f.write(f"{rel}\t{v}\t{d}\n")
    return 1 if counts["fail"] else 0


FILE_ARG = re.compile(r'\bfile\s*=\s*"((?:[^"\\]|\\.)*)"')


def vendor(checkout):
    """Writes tests/openscad_suite again from a checkout of openscad-2021.01."""
    src = os.path.join(checkout, "testdata", "scad")
    expected_dirs = {d: os.path.join(checkout, "tests", "regression", s) for d, s in (("expected", "cgalpngtest"), ("expected_preview", "opencsgtest"))}
    for sub in ("testdata", *expected_dirs):
        shutil.rmtree(os.path.join(SUITE, sub), ignore_errors=True)
        if sub != "testdata":
            os.makedirs(os.path.join(SUITE, sub))
    kept = skipped_image = skipped_export = 0
    for d, _, fs in sorted(os.walk(src)):
        for f in sorted(fs):
            if not f.endswith(".scad"):
                continue
            scad = os.path.join(d, f)
            rel = os.path.relpath(scad, src)[: -len(".scad")] + ".csg"
            found = [(d, os.path.join(e, test_name(rel) + "-expected.png")) for d, e in expected_dirs.items()]
            image = next(((d, p) for d, p in found if os.path.exists(p)), None)
            if image is None:
                skipped_image += 1
                continue
            out = os.path.join(SUITE, "testdata", "scad", rel)
            os.makedirs(os.path.dirname(out), exist_ok=True)
            try:
                p = subprocess.run(["openscad", "--render", "-o", out, f], cwd=d, capture_output=True, timeout=TIMEOUT)
            except subprocess.TimeoutExpired:
                p = None
            text = open(out, errors="replace").read() if os.path.exists(out) else ""
            if p is None or p.returncode != 0 or not re.search(r"\w+\s*\(", text.replace("group()", "")):
                skipped_export += 1
                if os.path.exists(out):
                    os.remove(out)
                continue
            # OpenSCAD writes each import's timestamp: not part of the model.
            text = re.sub(r",\s*timestamp\s*=\s*\d+", "", text)
            with open(out, "w") as g:
                g.write(text)
            for name in FILE_ARG.findall(text):
                data = os.path.normpath(os.path.join(d, name))
                if os.path.isfile(data) and os.path.commonpath([data, checkout]) == os.path.normpath(checkout):
                    to = os.path.join(SUITE, os.path.relpath(data, checkout))
                    os.makedirs(os.path.dirname(to), exist_ok=True)
                    shutil.copyfile(data, to)
            shutil.copyfile(image[1], os.path.join(SUITE, image[0], test_name(rel) + ".png"))
            kept += 1
    print(f"{kept} models kept; {skipped_image} without an expected image, {skipped_export} OpenSCAD exports no solid or shape from")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    ap.add_argument("--only", default="", help="comma-separated texts: only the files whose path holds one")
    ap.add_argument("--report", help="write every file's verdict here")
    ap.add_argument("--vendor", metavar="CHECKOUT", help="write tests/openscad_suite again from this checkout")
    a = ap.parse_args()
    if a.vendor:
        vendor(os.path.abspath(a.vendor))
        return 0
    return check(a.csgrt, a.only, a.report)


if __name__ == "__main__":
    sys.exit(main())
