#!/usr/bin/env python3
"""How csgrt's default picture compares with OpenSCAD's, side by side.

For each of OpenSCAD 2021.01's own examples (or the models given), renders
OpenSCAD's PNG export (`openscad -o x.png x.scad`: its preview, under
`xvfb-run` when there is no display) and csgrt's picture of the same program
with the same view (`--viewall --autocenter`, OpenSCAD's own default view;
both 512 x 384), writes a contact sheet of the pairs (OpenSCAD | csgrt) and
measures, over the pixels where both show the model (OpenSCAD's pixels that
are not its Cornfield background, #ffffe5, and csgrt's hit mask, less a
2-pixel band along either's edges):

- the brightest 1 % of the model's pixels (the 99th percentile of each
  channel): how far lit faces reach toward the base colour;
- the darkest 5 % of its luminance (Rec. 709 weights on the 8-bit values):
  whether faces turned from the light go black;
- the mean luminance and its spread (standard deviation): contrast.

Each figure is given for both programs and as csgrt's over OpenSCAD's.
The models' own colours count: a figure is a property of the picture, not
a colour science claim. Judge by looking, too: the sheet is the evidence.

Needs `openscad` (Debian: apt-get install -y openscad xvfb). Not in the CI line.

Usage: look.py [--csgrt BIN] [--out DIR] [--only NAME,...] [MODEL.scad ...]
Writes DIR/look.md and DIR/look.jpg (default: a temporary folder, printed).
"""

import argparse
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from tools import ROOT
from tools.dev.openscad_view import mixed, openscad_cmd

EXAMPLES = "/usr/share/openscad/examples"
W, H = 512, 384
BACKGROUND = np.array([255, 255, 229])
TIMEOUT = 300


def examples():
    return sorted(glob.glob(os.path.join(EXAMPLES, "*", "*.scad")))


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def figures(img, mask):
    px = img[mask].astype(float)
    lum = luminance(px)
    return {
        "p99": np.percentile(px, 99, axis=0),
        "dark5": float(np.percentile(lum, 5)),
        "mean": float(lum.mean()),
        "spread": float(lum.std()),
    }


def one(csgrt, model, work):
    name = os.path.splitext(os.path.basename(model))[0]
    theirs, ours, mask = (os.path.join(work, f"{name}_{k}.png") for k in ("openscad", "csgrt", "mask"))
    folder = os.path.dirname(model)
    r = subprocess.run([*openscad_cmd(), "-o", theirs, f"--imgsize={W},{H}", model], cwd=folder,
                       capture_output=True, text=True, timeout=TIMEOUT)
    if r.returncode != 0 or not os.path.exists(theirs):
        return name, None, f"OpenSCAD: {r.stderr.strip().splitlines()[-1] if r.stderr.strip() else r.returncode}"
    r = subprocess.run([csgrt, model, "--viewall", "--autocenter", "--size", f"{W}x{H}", "-o", ours, "--mask", mask, "-q"],
                       cwd=folder, capture_output=True, text=True, timeout=TIMEOUT)
    if r.returncode != 0:
        return name, None, f"csgrt: {r.stderr.strip().splitlines()[0] if r.stderr.strip() else r.returncode}"
    a = np.asarray(Image.open(theirs).convert("RGB")).astype(int)
    b = np.asarray(Image.open(ours).convert("RGB")).astype(int)
    m = np.asarray(Image.open(mask).convert("L")) > 127
    model_a = np.abs(a - BACKGROUND).sum(axis=2) > 6
    both = model_a & m & ~mixed(model_a) & ~mixed(m)
    if both.sum() < 200:
        return name, None, f"only {int(both.sum())} pixels of model in both"
    return name, (figures(a, both), figures(b, both), theirs, ours), None


def sheet(rows, path, per_row=2):
    pairs = [(Image.open(t), Image.open(o)) for _, (_, _, t, o) in rows]
    if not pairs:
        return
    cw, ch = W // 2, H // 2
    n = len(pairs)
    lines = (n + per_row - 1) // per_row
    out = Image.new("RGB", (per_row * 2 * cw + (per_row - 1) * 8, lines * ch), (255, 255, 255))
    for k, (t, o) in enumerate(pairs):
        x = (k % per_row) * (2 * cw + 8)
        y = (k // per_row) * ch
        out.paste(t.resize((cw, ch)), (x, y))
        out.paste(o.resize((cw, ch)), (x + cw, y))
    out.save(path, quality=90)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("models", nargs="*")
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target", "release", "csgrt"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--only", default=None, help="comma-separated example names")
    a = ap.parse_args()
    models = [os.path.abspath(m) for m in a.models] or examples()
    if a.only:
        keep = set(a.only.split(","))
        models = [m for m in models if os.path.splitext(os.path.basename(m))[0] in keep]
    out = a.out or tempfile.mkdtemp(prefix="look-")
    os.makedirs(out, exist_ok=True)
    csgrt = os.path.abspath(a.csgrt)
    rows, skipped = [], []
    with tempfile.TemporaryDirectory() as work:
        for m in models:
            name, got, why = one(csgrt, m, work)
            if got is None:
                skipped.append((name, why))
                print(f"{name}: skipped ({why})", file=sys.stderr)
                continue
            rows.append((name, got))
            ta, tb = got[0], got[1]
            print(f"{name}: brightest 1 % {ta['p99'].round().astype(int).tolist()} | {tb['p99'].round().astype(int).tolist()}; "
                  f"darkest 5 % {ta['dark5']:.0f} | {tb['dark5']:.0f}; mean {ta['mean']:.0f} | {tb['mean']:.0f}; "
                  f"spread {ta['spread']:.0f} | {tb['spread']:.0f}", flush=True)
        sheet(rows, os.path.join(out, "look.jpg"))
    ratio = lambda k: np.exp(np.mean([np.log(max(g[1][k], 1e-9) / max(g[0][k], 1e-9)) for _, g in rows]))
    p99 = lambda g, i: float(np.mean(g[i]["p99"]))
    lines = [
        "# csgrt's default picture beside OpenSCAD's",
        "",
        f"Written by `python -m tools.dev.look --out DIR` ({len(rows)} of OpenSCAD 2021.01's examples, {W}x{H},",
        "`--viewall --autocenter` for csgrt; OpenSCAD's PNG export as it is). Per model, OpenSCAD | csgrt,",
        "over the pixels both show as the model: the brightest 1 % (99th percentile, mean of R, G, B),",
        "the darkest 5 % of luminance, the mean luminance and its spread (8-bit values). OpenSCAD's",
        "default face colour, Cornfield #f9d72c, is 169 as a mean of R, G, B; the pictures, OpenSCAD's",
        "left of csgrt's, are `look.jpg`.",
        "",
        "| model | brightest 1 % | darkest 5 % | mean | spread |",
        "|---|---|---|---|---|",
    ]
    for name, g in rows:
        lines.append(f"| {name} | {p99(g, 0):.0f} \\| {p99(g, 1):.0f} | {g[0]['dark5']:.0f} \\| {g[1]['dark5']:.0f} | "
                     f"{g[0]['mean']:.0f} \\| {g[1]['mean']:.0f} | {g[0]['spread']:.0f} \\| {g[1]['spread']:.0f} |")
    if rows:
        lines += [
            "",
            "Geometric means of csgrt's figure over OpenSCAD's: "
            f"darkest 5 % {ratio('dark5'):.2f}, mean {ratio('mean'):.2f}, spread {ratio('spread'):.2f}; "
            f"brightest 1 %: {np.exp(np.mean([np.log(p99(g, 1) / p99(g, 0)) for _, g in rows])):.2f}.",
        ]
    if skipped:
        lines += ["", "Skipped: " + "; ".join(f"{n} ({w})" for n, w in skipped) + "."]
    with open(os.path.join(out, "look.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines[-3:]))
    print(f"wrote {out}/look.md and {out}/look.jpg")


if __name__ == "__main__":
    main()
