"""text(): OpenSCAD 2021.01's layout (src/FreetypeRenderer.cc), read with
HarfBuzz (uharfbuzz) for shaping and fontTools for the glyphs."""

import math
import os

import numpy as np

from tools import ROOT

from . import meaning

__all__ = ['FONT_DIR', 'FONT_FILES', '_FONTS', 'font', 'font_file', 'glyph_loops', 'text_2d']


# --------------------------------------------------------------------------
# text(): OpenSCAD 2021.01's layout (src/FreetypeRenderer.cc), read with
# HarfBuzz (uharfbuzz, the C library) for shaping and fontTools for the
# glyphs, from the font files csgrt builds in (fonts/).
# --------------------------------------------------------------------------

FONT_DIR = os.path.join(ROOT, "fonts")
FONT_FILES = {
    (False, False): "LiberationSans-Regular.ttf",
    (True, False): "LiberationSans-Bold.ttf",
    (False, True): "LiberationSans-Italic.ttf",
    (True, True): "LiberationSans-BoldItalic.ttf",
}
_FONTS = {}


def font_file(name):
    """The built-in face for a fontconfig name ("Family:style=Bold"): the
    oracle knows Liberation Sans only, and any other family falls back to
    it, as csgrt does on a machine without that family."""
    name = name.strip() or "Liberation Sans:style=Regular"
    props = [p.split("=", 1)[-1].lower() for p in name.split(":")[1:]]
    words = " ".join(props).replace("-", " ").split()
    bold = "bold" in words
    italic = any(w in ("italic", "oblique") for w in words)
    return os.path.join(FONT_DIR, FONT_FILES[(bold, italic)])


def font(path):
    if path not in _FONTS:
        import uharfbuzz as hb
        from fontTools.ttLib import TTFont

        tt = TTFont(path)
        face = hb.Face(hb.Blob.from_file_path(path))
        _FONTS[path] = (tt, tt.getGlyphSet(), hb.Font(face), tt.getGlyphOrder())
    return _FONTS[path]


def glyph_loops(glyph_set, name):
    """A glyph's contours in font units: loops of (point, control or None),
    TrueType's implied on-curve points made explicit by fontTools."""
    from fontTools.pens.basePen import BasePen

    class Pen(BasePen):
        def __init__(self):
            super().__init__(glyph_set)
            self.loops, self.cur = [], None

        def _moveTo(self, p):
            self.cur = [(np.array(p, float), None)]
            self.loops.append(self.cur)

        def _lineTo(self, p):
            self.cur.append((np.array(p, float), None))

        def _qCurveToOne(self, c, p):
            self.cur[-1] = (self.cur[-1][0], np.array(c, float))
            self.cur.append((np.array(p, float), None))

        def _curveToOne(self, c1, c2, p):
            raise ValueError("cubic glyph outlines are not in the oracle")

        def _closePath(self):
            l = self.cur
            if len(l) > 1 and np.array_equal(l[-1][0], l[0][0]):
                l.pop()
            self.cur = None

        _endPath = _closePath

    pen = Pen()
    glyph_set[name].draw(pen)
    out = []
    for l in pen.loops:
        # Zero-length straight edges are no edges.
        l = [e for i, e in enumerate(l) if e[1] is not None or not np.array_equal(e[0], l[(i + 1) % len(l)][0])]
        if len(l) >= 3 or len(l) == 2 and any(c is not None for _, c in l):
            out.append(l)
    return out


def text_2d(rd, s, a, place, placed=None):
    """The text's glyphs as one 2-D tree; with `placed` (a list), also each
    drawn glyph's (name, scale, shift): its font-unit point q lands at
    place(scale * q + shift)."""
    import uharfbuzz as hb

    text = a.get("text", "")
    if not isinstance(text, str):
        raise rd.err(s, "text of text must be a string")
    size = meaning.num(rd.path, s, a, "size", 10.0)
    spacing = meaning.num(rd.path, s, a, "spacing", 1.0)
    direction = a.get("direction", "")
    vertical = direction[:1].lower() in ("t", "b")
    tt, gs, hbfont, order = font(font_file(a.get("font", "")))
    buf = hb.Buffer()
    buf.add_str(text)
    if direction[:1].lower() in ("l", "r", "t", "b"):
        buf.direction = {"l": "ltr", "r": "rtl", "t": "ttb", "b": "btt"}[direction[:1].lower()]
    if a.get("script"):
        try:
            buf.script = a["script"]
        except Exception:
            pass
    if a.get("language", "en"):
        buf.language = a.get("language", "en")
    buf.guess_segment_properties()
    hb.shape(hbfont, buf, {})
    upem = tt["head"].unitsPerEm
    # FT_Set_Char_Size(face, 0, 1e5, 100, 100): the em in 26.6 units, the
    # ppem rounded to a whole pixel when head.flags bit 3 says so.
    # HarfBuzz through FreeType scales its positions by the em asked; the
    # TrueType driver loads outlines at the rounded one.
    em_asked = round(1e5 * 100 / 72)
    em = em_asked
    if tt["head"].flags & 8:
        em = math.floor((em + 32) / 64) * 64
    k_out, k_met = em / upem / 1e5, em_asked / upem / 1.024e5
    os2 = tt["OS/2"] if "OS/2" in tt else None
    v_adv = (os2.sTypoAscender - os2.sTypoDescender) if os2 is not None else (tt["hhea"].ascent - tt["hhea"].descent)
    glyphs, width, asc, desc = [], 0.0, 0.0, 0.0
    for info, pos in zip(buf.glyph_infos, buf.glyph_positions):
        name = order[info.codepoint]
        loops = glyph_loops(gs, name)
        pts = [q for l in loops for e in l for q in e if q is not None]
        lo0 = np.min(pts, axis=0) if pts else np.zeros(2)
        hi0 = np.max(pts, axis=0) if pts else np.zeros(2)
        # FreeType's grid-fitted control box (26.6 units, whole pixels).
        lo = np.floor(lo0 * em / upem / 64) * 64
        hi = np.ceil(hi0 * em / upem / 64) * 64
        if vertical:
            # FreeType's vertical metrics for a font without vmtx
            # (ttgload.c), as hb-ft reads them: the glyph moved by minus
            # (horiAdvance / 2, top of its box + (A - height) / 2 scaled),
            # A = sTypoAscender - sTypoDescender, then advanced by -A at
            # the em asked; 26.6 units, each scaling rounded.
            sc = em / upem
            rnd = lambda x: math.copysign(math.floor(abs(x) + 0.5), x)  # FT_MulFix: half away from 0
            h_adv = rnd(tt["hmtx"][name][0] * sc)
            top_box = rnd(hi0[1] * sc)
            height = rnd((top_box - rnd(lo0[1] * sc)) / sc)
            top = math.trunc((v_adv - height) / 2)
            off = -np.array([h_adv // 2, top_box + rnd(top * sc)], float) / 1.024e5
            adv = np.array([0.0, -rnd(v_adv * em_asked / upem)]) / 1.024e5
            width = max(width, (hi[0] - lo[0]) / 1.024e5)
            asc += adv[1] * spacing
            glyphs.append((loops, off, adv, name))
            continue
        asc, desc = max(asc, max(0.0, hi[1] / 1.024e5)), max(desc, max(0.0, -lo[1] / 1.024e5))
        adv = np.array([pos.x_advance, pos.y_advance], float) * k_met
        width += adv[0] * spacing
        glyphs.append((loops, np.array([pos.x_offset, pos.y_offset], float) * k_met, adv, name))
    halign, valign = a.get("halign", "left"), a.get("valign", "baseline")
    x0 = {"right": -width, "center": -width / 2}.get(halign, 0.0)
    y0 = {"top": -asc, "center": desc / 2 - asc / 2, "bottom": desc}.get(valign, 0.0)
    pen, parts = np.zeros(2), []
    for loops, off, adv, name in glyphs:
        shift = np.array([x0, y0]) + off + pen
        pen = pen + adv * spacing
        if not loops:
            continue
        if placed is not None:
            placed.append((name, size * k_out, size * shift))
        moved = [[(place([size * (q * k_out + shift)])[0], None if c is None else place([size * (c * k_out + shift)])[0]) for q, c in l] for l in loops]
        parts.append(("curves", moved))
    if not parts:
        return None
    return parts[0] if len(parts) == 1 else ("op", "union", parts)
