"""import(): an SVG drawing as OpenSCAD 2021.01 reads it (import_svg.cc over
its own libsvg), with the standard library's XML parser."""

import math
import re

import numpy as np

from . import plane

__all__ = ['SVG_ARC_TOLERANCE', 'SVG_CLIPPER', 'SVG_CMDS', 'SVG_NUM', 'arc_segment', 'part_moved', 'stroke_pieces', 'svg_arc', 'svg_arc_steps', 'svg_clipper', 'svg_length', 'svg_mm', 'svg_num', 'svg_openscad_points', 'svg_parts', 'svg_path', 'svg_points', 'svg_read', 'svg_stroke', 'svg_stroke_slack', 'svg_style', 'svg_tokens', 'svg_transform', 'svg_tree']


# --------------------------------------------------------------------------
# import(): an SVG drawing as OpenSCAD 2021.01 reads it (import_svg.cc over
# its own libsvg), read here with the standard library's XML parser and a
# path scanner of the oracle's own. The elements path, rect (round corners
# as four arcs), circle, ellipse, line, polyline and polygon outside defs,
# each under its own transform and those of its g, text and tspan
# ancestors; every closed outline filled, an open one (line, polyline, a
# path's subpath whose ends are more than 0.1 apart: when the path never
# closes, any such; else only those ended by a later M) stroked by
# Clipper's open offset (stroke-width, under 0.01 read as 1; linecap butt,
# round, square (default); linejoin miter with Clipper's limit 2 (default),
# round, and bevel as Clipper's square); one element's outlines even-odd,
# the elements united; the page in mm (px at 96 an inch, a bare number at
# the dpi, default 72), the viewBox mapped onto it by preserveAspectRatio,
# y flipped; center puts the box of OpenSCAD's own cut-up points (curves
# in 20 steps, arcs in |delta| 10 / 180 + 4, ellipses in 40, strokes as
# Clipper makes them) at the origin. The oracle's mesh strokes with
# pyclipper (Clipper 6.4.2, the library libsvg calls, on its 10^-4 grid);
# curves, arcs and ellipses it cuts itself, finer with n.
# --------------------------------------------------------------------------

SVG_CMDS = "MmZzLlHhVvCcSsQqTtAa"
SVG_NUM = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
# libsvg offsets strokes on Clipper's integer grid at 10^4 a unit, with
# Clipper's default round precision (ArcTolerance 0.25 grid units).
SVG_CLIPPER = 10000.0
SVG_ARC_TOLERANCE = 0.25


def svg_num(t):
    """libsvg's parse_double: the whole text a finite number, else 0."""
    if not isinstance(t, str) or t != t.strip() or "_" in t:
        return 0.0
    try:
        v = float(t)
    except ValueError:
        return 0.0
    return v if math.isfinite(v) else 0.0


def svg_style(e, name):
    """An attribute, or its value in the style attribute when absent
    (libsvg: items split at ';', each at ':' into exactly two, untrimmed)."""
    v = e.get(name)
    if v:
        return v
    for item in (e.get("style") or "").split(";"):
        kv = item.split(":")
        if len(kv) == 2 and kv[0] == name:
            return kv[1]
    return ""


def svg_transform(text):
    """The 3 x 3 matrix of an SVG transform list, applied right to left."""
    m = np.eye(3)
    for name, args in re.findall(r"(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)", text or ""):
        v = [float(x) for x in re.split(r"[\s,]+", args.strip()) if x]
        t = np.eye(3)
        if name == "matrix":
            t[:2, :] = [[v[0], v[2], v[4]], [v[1], v[3], v[5]]]
        elif name == "translate":
            t[:2, 2] = [v[0], v[1] if len(v) > 1 else 0.0]
        elif name == "scale":
            t[0, 0], t[1, 1] = v[0], v[1] if len(v) > 1 else v[0]
        elif name == "rotate":
            a = math.radians(v[0])
            r = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
            if len(v) == 3:
                c = np.eye(3)
                c[:2, 2] = v[1:3]
                ci = np.eye(3)
                ci[:2, 2] = [-v[1], -v[2]]
                r = c @ r @ ci
            t = r
        elif name == "skewX":
            t[0, 1] = math.tan(math.radians(v[0]))
        else:
            t[1, 0] = math.tan(math.radians(v[0]))
        m = m @ t
    return m


def svg_tokens(d):
    """Path data as commands and number texts (kept as text: an arc's
    flags may be written together, '0150' for 0, 1, 50)."""
    out, i = [], 0
    while i < len(d):
        ch = d[i]
        if ch in " \t\r\n,":
            i += 1
        elif ch in SVG_CMDS:
            out.append(ch)
            i += 1
        else:
            mt = SVG_NUM.match(d, i)
            if not mt:
                raise ValueError(f"path data: unexpected {ch!r} at character {i + 1}")
            out.append(mt.group())
            i = mt.end()
    return out


def svg_arc(a, b, r, rot, large, sweep):
    """(A, c, mid) of the SVG arc from a to b (SVG 1.1 F.6.5: radii grown
    when too small), 'line' for a zero radius, None for equal ends."""
    rx, ry = abs(r[0]), abs(r[1])
    if np.array_equal(a, b):
        return None
    if rx == 0 or ry == 0:
        return "line"
    ca, sa = math.cos(math.radians(rot)), math.sin(math.radians(rot))
    h = (a - b) / 2
    x1, y1 = ca * h[0] + sa * h[1], -sa * h[0] + ca * h[1]
    lam = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry)
    if lam > 1:
        rx, ry = rx * math.sqrt(lam), ry * math.sqrt(lam)
    num_ = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1
    k = math.sqrt(max(num_, 0.0) / (rx * rx * y1 * y1 + ry * ry * x1 * x1))
    if large == sweep:
        k = -k
    cx1, cy1 = k * rx * y1 / ry, -k * ry * x1 / rx
    c = np.array([ca * cx1 - sa * cy1, sa * cx1 + ca * cy1]) + (a + b) / 2
    t0 = math.atan2((y1 - cy1) / ry, (x1 - cx1) / rx)
    t1 = math.atan2((-y1 - cy1) / ry, (-x1 - cx1) / rx)
    dt = t1 - t0
    if sweep and dt < 0:
        dt += 2 * math.pi
    elif not sweep and dt > 0:
        dt -= 2 * math.pi
    A = np.array([[ca, -sa], [sa, ca]]) @ np.diag([rx, ry])
    tm = t0 + dt / 2
    return A, c, A @ np.array([math.cos(tm), math.sin(tm)]) + c


def svg_path(e, d):
    """The parts of a path's data: ('loop', pts, segs) for closed
    subpaths, ('stroke', ...) for open ones (libsvg's rule)."""
    toks = svg_tokens(d)
    subs, cur = [], None
    x = start = np.zeros(2)
    cmd, i = None, 0
    last_c = last_q = None
    closed_any = False

    def take():
        nonlocal i
        v = float(toks[i])
        i += 1
        return v

    def flag():
        nonlocal i
        t = toks[i]
        if t[0] in "01" and len(t) > 1 and t[1] not in ".eE":
            toks[i] = t[1:]
            return t[0] == "1"
        i += 1
        return float(t) != 0

    while i < len(toks):
        if toks[i] in SVG_CMDS and len(toks[i]) == 1:
            cmd = toks[i]
            i += 1
            if cmd in "Zz":
                if cur is not None:
                    subs.append((cur, True))
                cur, x, closed_any = None, start.copy(), True
                last_c = last_q = None
                continue
        if cmd is None:
            raise ValueError("path data does not start with a command")
        rel = cmd.islower()
        base = x if rel else np.zeros(2)
        if cmd in "Mm":
            if cur is not None:
                subs.append((cur, False))
            x = base + [take(), take()]
            start = x.copy()
            cur = ([x.copy()], [])
            cmd = "l" if rel else "L"
            last_c = last_q = None
            continue
        if cur is None:
            cur = ([x.copy()], [])
        pts, segs = cur
        nc = nq = None
        if cmd in "Ll":
            x = base + [take(), take()]
            seg = None
        elif cmd in "Hh":
            x = np.array([(x[0] if rel else 0.0) + take(), x[1]])
            seg = None
        elif cmd in "Vv":
            x = np.array([x[0], (x[1] if rel else 0.0) + take()])
            seg = None
        elif cmd in "Cc":
            c1, c2 = base + [take(), take()], base + [take(), take()]
            x = base + [take(), take()]
            seg, nc = ("C", c1, c2), c2
        elif cmd in "Ss":
            c1 = x + (x - last_c) if last_c is not None else x.copy()
            c2 = base + [take(), take()]
            x = base + [take(), take()]
            seg, nc = ("C", c1, c2), c2
        elif cmd in "Qq":
            c1 = base + [take(), take()]
            x = base + [take(), take()]
            seg, nq = ("Q", c1), c1
        elif cmd in "Tt":
            c1 = x + (x - last_q) if last_q is not None else x.copy()
            x = base + [take(), take()]
            seg, nq = ("Q", c1), c1
        else:
            r = (take(), take())
            rot = take()
            large, sweep = flag(), flag()
            b = base + [take(), take()]
            arc = svg_arc(x, b, r, rot, large, sweep)
            x = b
            last_c = last_q = None
            if arc is None:
                continue
            seg = None if arc == "line" else ("A",) + arc
        segs.append(seg)
        pts.append(x.copy())
        last_c, last_q = nc, nq
    if cur is not None:
        subs.append((cur, False))
    parts = []
    for k, ((pts, segs), closed) in enumerate(subs):
        opened = not closed and np.linalg.norm(pts[0] - pts[-1]) > 0.1 and (k + 1 < len(subs) or not closed_any)
        if opened:
            if any(sg is not None for sg in segs):
                raise ValueError("an open path with curves is stroked: not in the oracle")
            parts.append(svg_stroke(e, pts))
            continue
        pts, segs = list(pts), list(segs)
        if len(pts) > 1 and np.array_equal(pts[0], pts[-1]):
            pts.pop()
        else:
            segs.append(None)
        parts.append(("loop", pts, segs))
    return parts


def svg_stroke(e, pts):
    w = svg_num(svg_style(e, "stroke-width"))
    cap = {"butt": "butt", "round": "round"}.get(svg_style(e, "stroke-linecap"), "square")
    join = {"bevel": "square", "round": "round"}.get(svg_style(e, "stroke-linejoin"), "miter")
    return ("stroke", [np.asarray(p, float) for p in pts], 1.0 if w < 0.01 else w, cap, join)


def svg_points(t):
    v = [svg_num(x) for x in re.split(r"[\s,]+", (t or "").strip()) if x]
    return [np.array(v[j : j + 2]) for j in range(0, len(v) - 1, 2)]


def svg_parts(e, name):
    g = lambda k: svg_num(e.get(k, ""))
    if name == "path":
        return svg_path(e, e.get("d", ""))
    if name == "rect":
        x, y, w, h, rx, ry = g("x"), g("y"), g("width"), g("height"), g("rx"), g("ry")
        if abs(rx) >= 1e-8 or abs(ry) >= 1e-8:
            rx, ry = (ry if abs(rx) < 1e-8 else rx), (rx if abs(ry) < 1e-8 else ry)
            rx, ry = min(rx, w / 2), min(ry, h / 2)
            a = f"{rx} {ry} 0 0 1"
            d = f"M {x + rx} {y} H {x + w - rx} A {a} {x + w} {y + ry} V {y + h - ry} A {a} {x + w - rx} {y + h} H {x + rx} A {a} {x} {y + h - ry} V {y + ry} A {a} {x + rx} {y} z"
            return svg_path(e, d)
        return [("loop", [np.array(p, float) for p in ((x, y), (x + w, y), (x + w, y + h), (x, y + h))], [None] * 4)]
    if name in ("circle", "ellipse"):
        rx, ry = (g("r"), g("r")) if name == "circle" else (g("rx"), g("ry"))
        return [] if rx * ry == 0 else [("ellipse", np.diag([rx, ry]), np.array([g("cx"), g("cy")]))]
    if name == "line":
        return [svg_stroke(e, [np.array([g("x1"), g("y1")]), np.array([g("x2"), g("y2")])])]
    if name == "polyline":
        return [svg_stroke(e, svg_points(e.get("points")))]
    pts = svg_points(e.get("points"))
    return [("loop", pts, [None] * len(pts))]


def svg_length(t):
    mt = re.fullmatch(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(em|ex|px|in|cm|mm|pt|pc|%)?\s*", t or "")
    return None if not mt else (float(mt.group(1)), mt.group(2) or "")


def svg_mm(length, vb, dpi):
    if length is None:
        return 0.0 if vb is None else 25.4 * vb / dpi
    v, u = length
    k = {"": 25.4 / dpi, "px": 25.4 / 96, "pt": 25.4 / 72, "pc": 25.4 / 6, "in": 25.4, "cm": 10.0, "mm": 1.0}
    return v * k[u] if u in k else (0.0 if vb is None else vb)


def svg_page(el, dpi, page):
    """The page after libsvg reads svg element `el` (import_svg.cc): its
    height always; its scale, origin and alignment only where it has a
    viewBox (the alignment only where it aligns), else those of `page`."""
    height, scale, align, origin = page
    vb = None
    if el.get("viewBox") is not None:
        vb = [float(x) for x in re.split(r"[\s,]+", el.get("viewBox").strip())]
        if len(vb) != 4 or vb[2] <= 0 or vb[3] <= 0:
            raise ValueError("a viewBox of no size")
    width = svg_mm(svg_length(el.get("width")), vb[2] if vb else None, dpi)
    height = svg_mm(svg_length(el.get("height")), vb[3] if vb else None, dpi)
    if vb:
        origin = np.array(vb[:2])
        scale = np.array([width / vb[2], height / vb[3]])
        words = (el.get("preserveAspectRatio") or "xMidYMid meet").split()
        if words and words[0] == "defer":
            words = words[1:]
        al = words[0] if words else "xMidYMid"
        if al != "none":
            k = scale.max() if len(words) > 1 and words[1] == "slice" else scale.min()
            scale = np.array([k, k])
            pos = lambda code, pg, v: {"Mid": pg / 2 - k * v / 2, "Max": pg - k * v}.get(code, 0.0)
            align = np.array([pos(al[1:4], width, vb[2]), pos(al[5:8], height, vb[3])])
    return height, scale, align, origin


def svg_read(path, dpi, center):
    """(shapes, place): each shape (its transform, its parts) in user
    space, and the map from user space to OpenSCAD's plane.

    libsvg reads tags in a stream: a start tag of svg, g, text or tspan
    pushes a container (an svg's with no transform of its own), an end tag
    of g, text or tspan pops the last one pushed, whichever it is (so an
    svg inside a group is popped by the group's end, and the group stays);
    a shape takes the transforms of the containers up to the first one
    pushed. Every svg element sets the page as it comes; the last one
    places the drawing, and center's box scales each shape by the page of
    its time."""
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    local = lambda el: el.tag.split("}")[-1]
    if local(root) != "svg":
        raise ValueError("the root element is not svg")

    def tags(el):
        yield el, True
        for ch in el:
            if isinstance(ch.tag, str):
                yield from tags(ch)
        yield el, False

    page = (0.0, np.ones(2), np.zeros(2), np.zeros(2))
    shapes, scales, open_, defs = [], [], [], 0
    for el, start in tags(root):
        name = local(el)
        if name == "defs":
            defs += 1 if start else -1
            continue
        if defs:
            continue
        if not start:
            if name in ("g", "text", "tspan"):
                open_.pop()
            continue
        m = open_[-1] if open_ else np.eye(3)
        if name == "svg":
            page = svg_page(el, dpi, page)
            open_.append(m)
        elif name in ("g", "text", "tspan"):
            open_.append(m @ svg_transform(el.get("transform")))
        elif name in ("path", "rect", "circle", "ellipse", "line", "polyline", "polygon"):
            shapes.append((m @ svg_transform(el.get("transform")), svg_parts(el, name)))
            scales.append(page[1])
    height, scale, align, origin = page
    if center:
        pts = []
        for (m, parts), k in zip(shapes, scales):
            for x in parts:
                pts += [(m[:2, :2] @ q + m[:2, 2]) * k for q in svg_openscad_points(x)]
        pts = np.array(pts) if pts else np.zeros((1, 2))
        cx, cy = (pts.min(axis=0) + pts.max(axis=0)) / 2
    else:
        cx, cy = -align[0], height - align[1]
    place = np.array([[scale[0], 0, -scale[0] * origin[0] - cx], [0, -scale[1], -scale[1] * origin[1] + cy], [0, 0, 1]])
    return shapes, place


def svg_clipper(x):
    """libsvg's stroke: Clipper's open offset of the polyline on its 10^4
    grid (pyclipper is Clipper 6.4.2, the library libsvg calls)."""
    import pyclipper

    _, pts, w, cap, join = x
    co = pyclipper.PyclipperOffset()
    jt = {"miter": pyclipper.JT_MITER, "round": pyclipper.JT_ROUND, "square": pyclipper.JT_SQUARE}[join]
    et = {"butt": pyclipper.ET_OPENBUTT, "round": pyclipper.ET_OPENROUND, "square": pyclipper.ET_OPENSQUARE}[cap]
    co.AddPath([(int(p[0] * SVG_CLIPPER), int(p[1] * SVG_CLIPPER)) for p in pts], jt, et)
    return [np.array(r, float) / SVG_CLIPPER for r in co.Execute(w * SVG_CLIPPER / 2)]


def svg_arc_steps(A, c, a, b, mid, step):
    """Points of an arc from a through mid to b at most `step` radians of
    its ellipse's parameter apart (a first, b not)."""
    Ai = np.linalg.inv(A)
    ang = lambda p: math.atan2(*(Ai @ (p - c))[::-1])
    t0, tm, t1 = ang(a), ang(mid), ang(b)
    fwd = (t1 - t0) % (2 * math.pi)
    dt = fwd if (tm - t0) % (2 * math.pi) < fwd else fwd - 2 * math.pi
    k = max(1, math.ceil(abs(dt) / step))
    return [a] + [A @ np.array([math.cos(t0 + dt * j / k), math.sin(t0 + dt * j / k)]) + c for j in range(1, k)]


def svg_openscad_points(x):
    """OpenSCAD's cut-up points of a part (for center's box)."""
    if x[0] == "ellipse":
        return [x[1] @ np.array([math.sin(math.radians(9 * i)), math.cos(math.radians(9 * i))]) + x[2] for i in range(1, 41)]
    if x[0] == "stroke":
        return [q for r in svg_clipper(x) for q in r]
    _, pts, segs = x
    out = []
    for i, sg in enumerate(segs):
        a, b = pts[i], pts[(i + 1) % len(pts)]
        out.append(a)
        if sg is None:
            continue
        if sg[0] in "QC":
            P = plane.bezier_points(a, sg[1] if sg[0] == "Q" else np.array(sg[1:3]), b)
            out += list(plane.bezier_eval(P, np.arange(1, 21) / 20))
        else:
            A, c, mid = sg[1:]
            Ai = np.linalg.inv(A)
            t0 = math.atan2(*(Ai @ (a - c))[::-1])
            tm = math.atan2(*(Ai @ (mid - c))[::-1])
            t1 = math.atan2(*(Ai @ (b - c))[::-1])
            fwd = (t1 - t0) % (2 * math.pi)
            dt = fwd if (tm - t0) % (2 * math.pi) < fwd else fwd - 2 * math.pi
            steps = int(abs(math.degrees(dt)) * 10 / 180 + 4)
            out += [A @ np.array([math.cos(t0 + dt * j / steps), math.sin(t0 + dt * j / steps)]) + c for j in range(steps + 1)]
    return out


def stroke_pieces(x):
    """A stroke's exact region as the oracle's pieces (Clipper's open
    offset without its grid): each segment's band, the ends (square: the
    band carried on by half the width; round: a disc), and at each corner
    on its outer side a disc (round), the miter kite up to a turn of 120
    degrees (Clipper's miter limit 2), else the kite cut across the
    bisector at half the width; a reversal squared like an end."""
    _, raw, w, cap, join = x
    pts = [raw[0]] if raw else []
    for p in raw[1:]:
        if not np.array_equal(p, pts[-1]):
            pts.append(p)
    if len(pts) < 2:
        return []
    r = w / 2
    disc = lambda c: ("ellipse", np.eye(2) * r, np.asarray(c, float))
    poly = lambda v: ("poly", [np.array(v)])
    t = [(b - a) / np.linalg.norm(b - a) for a, b in zip(pts[:-1], pts[1:])]
    nrm = lambda d: np.array([-d[1], d[0]])
    out = [poly([a - r * nrm(d), b - r * nrm(d), b + r * nrm(d), a + r * nrm(d)]) for a, b, d in zip(pts[:-1], pts[1:], t)]
    for p, d in ((pts[0], -t[0]), (pts[-1], t[-1])):
        if cap == "round":
            out.append(disc(p))
        elif cap == "square":
            out.append(poly([p - r * nrm(d), p + r * d - r * nrm(d), p + r * d + r * nrm(d), p + r * nrm(d)]))
    for p, t1, t2 in zip(pts[1:-1], t[:-1], t[1:]):
        cross, cos = t1[0] * t2[1] - t1[1] * t2[0], float(t1 @ t2)
        if cross == 0 and cos > 0:
            continue
        if join == "round":
            out.append(disc(p))
            continue
        if cross == 0:
            out.append(poly([p - r * nrm(t1), p + r * t1 - r * nrm(t1), p + r * t1 + r * nrm(t1), p + r * nrm(t1)]))
            continue
        side = -1.0 if cross > 0 else 1.0
        m1, m2 = side * nrm(t1), side * nrm(t2)
        if join == "miter" and 1 + cos >= 0.5:
            out.append(poly([p, p + r * m1, p + (m1 + m2) * (r / (1 + cos)), p + r * m2]))
        else:
            s_ = r * math.tan(math.atan2(abs(cross), cos) / 4)
            out.append(poly([p, p + r * m1, p + r * m1 + s_ * t1, p + r * m2 - s_ * t2, p + r * m2]))
    return out


def arc_segment(a, b, A, c, mid):
    """The ellipse A u + c on mid's side of the chord a-b (the ellipse met
    with a rectangle there holding all of it, as csgrt builds it)."""
    t = (b - a) / np.linalg.norm(b - a)
    n = np.array([-t[1], t[0]])
    if (mid - a) @ n < 0:
        n = -n
    d = np.linalg.norm(c - a) + np.linalg.norm(A[:, 0]) + np.linalg.norm(A[:, 1]) + np.linalg.norm(b - a)
    rect = np.array([a - t * d, b + t * d, b + t * d + n * d, a - t * d + n * d])
    return ("op", "intersection", [("ellipse", A, c), ("poly", [rect])])


def part_moved(x, m):
    """A part of an SVG shape moved by the 3 x 3 matrix m."""
    mv = lambda q: m[:2, :2] @ q + m[:2, 2]
    if x[0] == "ellipse":
        return ("ellipse", m[:2, :2] @ x[1], mv(x[2]))
    if x[0] == "polys":
        return ("polys", [r @ m[:2, :2].T + m[:2, 2] for r in x[1]])
    segs = []
    for sg in x[2]:
        if sg is None:
            segs.append(None)
        elif sg[0] == "A":
            segs.append(("A", m[:2, :2] @ sg[1], mv(sg[2]), mv(sg[3])))
        else:
            segs.append((sg[0],) + tuple(mv(q) for q in sg[1:]))
    return ("loop", [mv(q) for q in x[1]], segs)


def svg_tree(shapes, place):
    """The drawing as the oracle's 2-D tree, as csgrt builds it: per
    element, its loops (curves exact, an arc as its chord) by parity with
    each arc's segment, its ellipses and its strokes; the elements united.
    A 4th element carries each element's parts for the oracle's own mesh
    (strokes as Clipper's polygons)."""
    kids, mesh = [], []
    for m, parts in shapes:
        loops, odd, own = [], [], []
        for x in parts:
            if x[0] == "ellipse":
                odd.append(x)
                own.append(x)
            elif x[0] == "stroke":
                pieces = stroke_pieces(x)
                if pieces:
                    odd.append(pieces[0] if len(pieces) == 1 else ("op", "union", pieces))
                own.append(("polys", svg_clipper(x)))
            else:
                _, pts, segs = x
                loop = []
                for i, sg in enumerate(segs):
                    a, b = pts[i], pts[(i + 1) % len(pts)]
                    if sg is not None and sg[0] == "A":
                        odd.append(arc_segment(a, b, *sg[1:]))
                    ctrl = None if sg is None or sg[0] == "A" else sg[1] if sg[0] == "Q" else np.array(sg[1:3])
                    loop.append((np.asarray(a, float), ctrl))
                if len(pts) >= 3 or any(c is not None for _, c in loop):
                    loops.append(loop)
                own.append(x)
        tree = []
        if loops:
            curved = any(c is not None for l in loops for _, c in l)
            tree.append(("curves", loops) if curved else ("poly", [np.array([q for q, _ in l]) for l in loops]))
        tree += odd
        if not tree:
            continue
        mm = place @ m
        kids.append(plane.flat_moved(tree[0] if len(tree) == 1 else ("op", "xor", tree), mm))
        mesh.append((mm, [part_moved(x, mm) for x in own], max([svg_stroke_slack(x) for x in parts if x[0] == "stroke"], default=(0.0, 0.0))))
    if not kids:
        return None
    return ("op", "union", kids, ("svg", mesh))


def svg_stroke_slack(x):
    """(distance, angle) by which Clipper's stroke may stand off the exact
    one, in the element's own units: its input truncated and its output
    rounded to the 10^-4 grid (2 x 1.5 x 10^-4) plus its round parts'
    tolerance (2.5 x 10^-5); the normals of segments turned by the grid
    (3 x 10^-4 over the shortest), and a round part cut into steps of
    2 acos(1 - tolerance / half width)."""
    _, pts, w, cap, join = x
    lens = [float(np.linalg.norm(b - a)) for a, b in zip(pts[:-1], pts[1:])]
    lens = [l for l in lens if l > 0]
    ang = 3e-4 / min(lens) if lens else 0.0
    if cap == "round" or join == "round":
        ang = max(ang, 2 * math.acos(max(-1.0, 1 - SVG_ARC_TOLERANCE / (w / 2 * SVG_CLIPPER))))
    return 3e-4 + SVG_ARC_TOLERANCE / SVG_CLIPPER, ang
