#!/usr/bin/env python3
"""A scene's text as POV-Ray's own `text` objects, for tools/bench/bench.py.

csgrt's --export-pov writes each glyph of an extruded text() as a POV-Ray
`prism` of the glyph's curves. POV-Ray has its own construction for text,
`text { ttf FILE STRING thickness, offset }`, which reads the TrueType
outlines itself; issue 14 asks for the speed of both. This tool rewrites an
export: every `prism` is replaced by one single-character `text` object a
glyph, from the same font file (fonts/), placed where OpenSCAD's layout puts
the glyph — the layout is the oracle's (tools/oracle/scene/: HarfBuzz and
fontTools, independent of csgrt). POV-Ray sets a one-character string with
its left edge (the glyph's xMin) at x = 0 and one font unit 1/upem, so the
object is scaled by the layout's scale times upem and moved by the glyph's
shift plus its xMin.

It reads only what tools/bench/bench_scenes.py writes for text: top-level
statements `translate([x, y, z]) linear_extrude(height = h) text("...",
size = s);`, besides any other solids (not text). Anything else that makes
prisms stops it with a message, as does a glyph count that does not match
the export's prisms. A glyph that is one rectangle on the axes ("l", "-",
"I" in Liberation Sans) csgrt extrudes as a box, and POV-Ray's `box` of
the export stands for it.

Usage: pov_text.py SCENE.csg EXPORT.pov OUT.pov
"""

import os
import re
import sys

from tools.oracle import scene  # noqa: E402

STATEMENT = re.compile(
    r'^translate\(\[([^\]]*)\]\) linear_extrude\(height = ([^)]*)\) '
    r'text\("((?:[^"\\]|\\.)*)", size = ([^)]*)\);$'
)
PRISM = re.compile(r"^  prism \{.*?^  \}\n", re.S | re.M)


class _Reader:
    path = "<pov_text>"

    def err(self, s, msg):
        return SystemExit(f"pov_text: {msg}")


def axis_rectangle(tt, name):
    """Whether the glyph's outline is one contour of four points on the
    curve, its sides along the axes (csgrt's `Outlines::axis_rectangle`:
    the layout only scales and moves it)."""
    g = tt["glyf"][name]
    if g.numberOfContours != 1:
        return False
    coords, ends, flags = g.getCoordinates(tt["glyf"])
    pts = list(coords)
    if len(pts) != 4 or not all(f & 1 for f in flags):
        return False
    sides = all((pts[i][0] == pts[(i + 1) % 4][0]) != (pts[i][1] == pts[(i + 1) % 4][1]) for i in range(4))
    xs, ys = {p[0] for p in pts}, {p[1] for p in pts}
    return sides and len(xs) == 2 and len(ys) == 2


def glyph_objects(csg_text):
    """[(POV-Ray text object without texture, …)] for the scene's text
    statements, in order, and how many prisms they stand for."""
    font_path = scene.font_file("")
    tt = scene.font(font_path)[0]
    upem = tt["head"].unitsPerEm
    cmap = {name: code for code, name in tt.getBestCmap().items()}
    objects = []
    for line in csg_text.splitlines():
        line = line.strip()
        if "text(" not in line:
            if "linear_extrude" in line:
                raise SystemExit(f"pov_text: an extrusion that is not text: {line}")
            continue
        m = STATEMENT.match(line)
        if not m:
            raise SystemExit(f"pov_text: a text statement not of the bench's form: {line}")
        tx, ty, tz = (float(v) for v in m.group(1).split(","))
        height, string, size = float(m.group(2)), m.group(3), float(m.group(4))
        string = re.sub(r"\\(.)", r"\1", string)
        placed = []
        scene.text_2d(_Reader(), None, {"text": string, "size": size}, lambda pts: pts, placed)
        for name, k, shift in placed:
            if axis_rectangle(tt, name):
                # csgrt extrudes a glyph that is one rectangle on the axes
                # as a box, exported as POV-Ray's `box`: it stands as it is.
                continue
            if name not in cmap:
                raise SystemExit(f"pov_text: glyph {name} (a ligature?) has no character of its own")
            ch = chr(cmap[name]).replace("\\", "\\\\").replace('"', '\\"')
            x_min = tt["glyf"][name].xMin
            sc, x, y = float(k * upem), float(k * x_min + shift[0] + tx), float(shift[1] + ty)
            objects.append(f'text {{ ttf "{os.path.abspath(font_path)}" "{ch}" 1, 0 '
                           f"scale <{sc!r}, {sc!r}, {height!r}> translate <{x!r}, {y!r}, {tz!r}>")
    return objects


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    csg, export, out = sys.argv[1:]
    with open(csg) as f:
        objects = glyph_objects(f.read())
    with open(export) as f:
        pov = f.read()
    prisms = PRISM.findall(pov)
    if len(prisms) != len(objects):
        raise SystemExit(f"pov_text: {len(prisms)} prisms in {export}, {len(objects)} glyphs in {csg}")
    it = iter(objects)

    def swap(m):
        texture = re.search(r"texture \{.*\} \}", m.group(0))
        if not texture:
            raise SystemExit(f"pov_text: a prism without its texture in {export}")
        return f"  {next(it)}\n    {texture.group(0)}\n  }}\n"

    with open(out, "w") as f:
        f.write(PRISM.sub(swap, pov))


if __name__ == "__main__":
    main()
