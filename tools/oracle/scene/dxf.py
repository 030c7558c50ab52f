"""import(): a DXF drawing as OpenSCAD 2021.01 reads it (src/dxfdata.cc), parsed
by ezdxf; meshes and surface() height maps."""

import math
import os
import re

import numpy as np

from . import meaning
from . import plane
from . import svg

__all__ = ['DXF_GRID', 'drawing_tree', 'dxf_paths', 'dxf_pieces', 'import_2d', 'import_mesh', 'merged', 'surface_mesh']


# --------------------------------------------------------------------------
# import(): a DXF drawing as OpenSCAD 2021.01 reads it (src/dxfdata.cc),
# parsed by ezdxf: LINE, LWPOLYLINE, ARC, CIRCLE and INSERT entities of the
# layer, points moved by -origin and scaled, pieces joined into paths where
# their ends meet on a 2^-20 grid (open chains first, each closed by a
# straight edge, then the closed loops), filled even-odd. Arcs stay arcs.
# --------------------------------------------------------------------------

DXF_GRID = 2.0**-20


def dxf_pieces(path, layer, origin, scale):
    """(pieces, circles): pieces (a, b, arc) with arc None or (centre,
    radius, a point of the arc between its ends)."""
    import ezdxf

    doc = ezdxf.readfile(path)
    pieces, circles = [], []

    def add(e, m, k):
        t = e.dxftype()
        if t == "LINE":
            pieces.append((m(e.dxf.start), m(e.dxf.end), None))
        elif t == "LWPOLYLINE":
            v = [m(p) for p in e.get_points("xy")]
            pieces.extend((v[i], v[i + 1], None) for i in range(len(v) - 1))
            if e.closed and len(v) > 1:
                pieces.append((v[-1], v[0], None))
        elif t == "CIRCLE":
            circles.append((m(e.dxf.center), e.dxf.radius * k))
        elif t == "ARC":
            a0, a1 = e.dxf.start_angle, e.dxf.end_angle
            if a1 <= a0:
                a1 += 360.0
            c, r = np.array([e.dxf.center[0], e.dxf.center[1]], float), e.dxf.radius
            at = lambda a: c + r * np.array([math.cos(math.radians(a)), math.sin(math.radians(a))])
            pieces.append((m(at(a0)), m(at(a1)), (m(c), r * k, m(at((a0 + a1) / 2)))))

    place = lambda p: (np.array([p[0], p[1]], float) - origin) * scale
    for e in doc.modelspace():
        if layer and e.dxf.layer != layer:
            continue
        if e.dxftype() == "INSERT":
            blk = doc.blocks.get(e.dxf.name)
            if blk is None:
                continue
            a = math.radians(e.dxf.rotation)
            sx, sy = e.dxf.xscale, e.dxf.yscale
            at = np.array([e.dxf.insert[0], e.dxf.insert[1]], float)

            def m(p, a=a, sx=sx, sy=sy, at=at):
                q = np.array([p[0] * sx, p[1] * sy])
                return place(np.array([math.cos(a) * q[0] - math.sin(a) * q[1], math.sin(a) * q[0] + math.cos(a) * q[1]]) + at)

            for be in blk:
                add(be, m, scale * abs(sx))
            continue
        add(e, place, scale)
    return pieces, circles


def dxf_paths(pieces):
    """Closed paths [(point, arc or None)] from pieces joined at their ends."""
    pts, keys = [], {}

    def key(p):
        i, j = round(p[0] / DXF_GRID), round(p[1] / DXF_GRID)
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                k = keys.get((i + di, j + dj))
                if k is not None and abs(pts[k][0] - p[0]) <= DXF_GRID and abs(pts[k][1] - p[1]) <= DXF_GRID:
                    return k
        pts.append(np.asarray(p, float))
        keys[(i, j)] = len(pts) - 1
        return len(pts) - 1

    ends = [(key(a), key(b)) for a, b, _ in pieces]
    at = {}
    for i, (a, b) in enumerate(ends):
        at.setdefault(a, []).append(i)
        at.setdefault(b, []).append(i)
    used = [False] * len(pieces)

    def walk(i, point):
        chain = []
        while True:
            used[i] = True
            fwd = ends[i][0] == point
            chain.append((i, fwd))
            point = ends[i][1] if fwd else ends[i][0]
            nxt = [k for k in at[point] if not used[k]]
            if not nxt:
                return chain, point
            i = nxt[0]

    def as_path(chain):
        """A chain's (start point as walked, arc) per piece."""
        return [(pts[ends[k][0] if f else ends[k][1]], pieces[k][2]) for k, f in chain]

    paths, n_open = [], 0
    for i in range(len(pieces)):
        for end in ends[i]:
            if not used[i] and ends[i][0] != ends[i][1] and sum(not used[k] for k in at[end]) == 1:
                chain, last = walk(i, end)
                n_open += 1
                path = as_path(chain) + [(pts[last], None)]
                if len(path) >= 3:
                    paths.append(path)
    for i in range(len(pieces)):
        if not used[i]:
            chain, last = walk(i, ends[i][0])
            path = as_path(chain)
            paths.append(path)
    return paths, n_open


def merged(pts, faces):
    """(points, faces) with identical points made one (−0 as 0)."""
    uniq, inv = np.unique(pts + 0.0, axis=0, return_inverse=True)
    inv = inv.reshape(-1)
    return uniq, [[int(inv[i]) for i in f] for f in faces]


def surface_mesh(rd, s, a):
    """(points, faces) of OpenSCAD 2021.01's surface() (surface.cc, read
    here on its own): the heights of a PNG (row h - 1 - y, column x,
    100/255 of 0.2126 r + 0.7152 g + 0.0722 b, or of 1 minus that when
    inverted) or of a .dat grid; each cell four triangles to its centre,
    walls down to min(0, lowest - 1), the bottom one polygon."""
    path = os.path.join(os.path.dirname(os.path.abspath(rd.path)), a["file"])
    with open(path, "rb") as f:
        data = f.read()
    z = {}
    if data[:8] == bytes([0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A]):
        from PIL import Image
        import io

        img = np.asarray(Image.open(io.BytesIO(data)).convert("RGBA"), dtype=float)
        h, w = img.shape[:2]
        for y in range(h):
            for x in range(w):
                p = 0.2126 * img[y, x, 0] + 0.7152 * img[y, x, 1] + 0.0722 * img[y, x, 2]
                z[(h - 1 - y, x)] = 100.0 / 255 * ((1 - p) if a.get("invert", False) else p)
    else:
        row = 0
        done = False
        for line in data.decode("utf-8", "replace").splitlines():
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            for col, word in enumerate(w for w in re.split(r"[ \t]", line) if w):
                try:
                    z[(row, col)] = float(word)
                except ValueError:
                    done = True
                    break
            if done:
                break
            row += 1
    if not z:
        return None, None
    rows = max(k[0] for k in z) + 1
    cols = max(k[1] for k in z) + 1
    if rows < 2 or cols < 2:
        return None, None
    low = min(0.0, min(v - 1 for v in z.values()))
    ox, oy = (-(cols - 1) / 2, -(rows - 1) / 2) if a.get("center", False) else (0.0, 0.0)
    Z = lambda i, j: z.get((i, j), 0.0)
    pts, faces = [], []

    def face(*ps):
        faces.append(list(range(len(pts), len(pts) + len(ps))))
        pts.extend([ox + x, oy + y, zz] for x, y, zz in ps)

    for i in range(1, rows):
        for j in range(1, cols):
            v1, v2, v3, v4 = Z(i - 1, j - 1), Z(i - 1, j), Z(i, j - 1), Z(i, j)
            vx = (v1 + v2 + v3 + v4) / 4
            c = (j - 0.5, i - 0.5, vx)
            face((j - 1, i - 1, v1), (j, i - 1, v2), c)
            face((j, i - 1, v2), (j, i, v4), c)
            face((j, i, v4), (j - 1, i, v3), c)
            face((j - 1, i, v3), (j - 1, i - 1, v1), c)
    for i in range(1, rows):
        face((0, i - 1, low), (0, i - 1, Z(i - 1, 0)), (0, i, Z(i, 0)), (0, i, low))
        face((cols - 1, i, low), (cols - 1, i, Z(i, cols - 1)), (cols - 1, i - 1, Z(i - 1, cols - 1)), (cols - 1, i - 1, low))
    for j in range(1, cols):
        face((j, 0, low), (j, 0, Z(0, j)), (j - 1, 0, Z(0, j - 1)), (j - 1, 0, low))
        face((j - 1, rows - 1, low), (j - 1, rows - 1, Z(rows - 1, j - 1)), (j, rows - 1, Z(rows - 1, j)), (j, rows - 1, low))
    rim = [(j, 0) for j in range(cols - 1)] + [(cols - 1, i) for i in range(rows - 1)]
    rim += [(j, rows - 1) for j in range(cols - 1, 0, -1)] + [(0, i) for i in range(rows - 1, 0, -1)]
    face(*[(x, y, low) for x, y in reversed(rim)])
    pts = np.array(pts, dtype=float)
    return merged(pts, faces)


def import_mesh(rd, s, a):
    """(points, faces) of a mesh file, read here: STL (binary when its size
    is 84 + 50 n for the n in its header, else ASCII `vertex` lines) and
    OFF; identical points merged."""
    file = a.get("file", a.get("filename"))
    path = os.path.join(os.path.dirname(os.path.abspath(rd.path)), file)
    with open(path, "rb") as f:
        data = f.read()
    ext = file.lower().rsplit(".", 1)[-1]
    if ext == "stl":
        n = int.from_bytes(data[80:84], "little") if len(data) >= 84 else -1
        if len(data) == 84 + 50 * n:
            rec = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
            pts = rec["v"].reshape(-1, 3).astype(float)
        else:
            vals = [ln.split()[1:4] for ln in data.decode().splitlines() if ln.strip().startswith("vertex")]
            pts = np.array(vals, dtype=float)
        faces = np.arange(len(pts)).reshape(-1, 3)
    elif ext == "off":
        words = [ln.split("#")[0].split() for ln in data.decode().splitlines()]
        words = [w for w in words if w]
        head = words.pop(0)
        if head[0] == "OFF":
            head = head[1:] or words.pop(0)
        nv, nf = int(head[0]), int(head[1])
        pts = np.array([w[:3] for w in words[:nv]], dtype=float)
        faces = [[int(x) for x in w[1 : 1 + int(w[0])]] for w in words[nv : nv + nf]]
    elif ext == "amf":
        import io
        import xml.etree.ElementTree as ET
        import zipfile

        if data[:2] == b"PK":
            with zipfile.ZipFile(io.BytesIO(data)) as z:
                data = z.read(z.namelist()[0])
        root = ET.fromstring(data)
        pts, faces = [], []
        for mesh in root.iter("mesh"):
            base = len(pts)
            for v in mesh.find("vertices").iter("vertex"):
                c = v.find("coordinates")
                pts.append([float(c.find(k).text) for k in ("x", "y", "z")])
            for t in mesh.iter("triangle"):
                faces.append([base + int(t.find(k).text) for k in ("v1", "v2", "v3")])
        pts = np.array(pts, dtype=float)
    else:
        raise rd.err(s, f"import of .{ext} is not in the oracle")
    return merged(pts, faces)


def import_2d(rd, s, a):
    file = a.get("file", a.get("filename"))
    if not isinstance(file, str):
        raise rd.err(s, "import needs a file")
    path = os.path.join(os.path.dirname(os.path.abspath(rd.path)), file)
    if file.lower().endswith(".svg"):
        dpi = meaning.num(rd.path, s, a, "dpi", 72.0)
        return svg.svg_tree(*svg.svg_read(path, dpi if dpi >= 0.001 else 72.0, bool(a.get("center", False))))
    if not file.lower().endswith(".dxf"):
        raise rd.err(s, f"import of {file} is not in the oracle")
    origin = np.array(a.get("origin", [0.0, 0.0])[:2], float)
    pieces, circles = dxf_pieces(path, a.get("layer", a.get("layername", "")) or "", origin, meaning.num(rd.path, s, a, "scale", 1.0))
    paths, _ = dxf_paths(pieces)
    # A single arc closing on itself is a whole circle.
    circles += [(path[0][1][0], path[0][1][1]) for path in paths if len(path) == 1 and path[0][1] is not None]
    return drawing_tree([p for p in paths if len(p) >= 2], circles)


def drawing_tree(paths, circles):
    """A drawing as the oracle's 2-D tree: each path the polygon of its
    chords minus the circular segments (the disc cut by the chord's
    half-plane on the arc's side) of arcs bulging inward, plus those bulging
    outward, a circle a disc; nested paths (a point of one's boundary inside
    another) combined even-odd: each path of even depth minus the paths of
    the next depth inside it. A 4th element carries the paths and circles
    for the oracle's own mesh."""
    disc = lambda c, r: ("ellipse", np.eye(2) * r, np.asarray(c, float))
    regions = []  # (tree, inside(x), probe)
    for c, r in circles:
        c = np.asarray(c, float)
        regions.append((disc(c, r), lambda x, c=c, r=r: np.linalg.norm(x - c) <= r, c + np.array([r, 0.0])))
    for path in paths:
        pts = [p for p, _ in path]
        chord = np.array(pts) if len(pts) >= 3 else None
        segs, inward, outward = [], [], []
        for i, (a, arc) in enumerate(path):
            if arc is None:
                continue
            b = path[(i + 1) % len(path)][0]
            c, r, mid = arc
            t = (b - a) / np.linalg.norm(b - a)
            n = np.array([-t[1], t[0]])
            if (mid - a) @ n < 0:
                n = -n
            rect = np.array([a - 2 * r * t, b + 2 * r * t, b + 2 * r * t + 2 * r * n, a - 2 * r * t + 2 * r * n])
            seg = ("op", "intersection", [disc(c, r), ("poly", [rect])])
            out = chord is None or not plane.even_odd_inside([chord], mid)
            (outward if out else inward).append(seg)
            segs.append((a, b, c, r, mid, out))
        parts = []
        if chord is not None:
            parts.append(("poly", [chord]) if not inward else ("op", "difference", [("poly", [chord])] + inward))
        parts += outward
        if not parts:
            continue
        tree = parts[0] if len(parts) == 1 else ("op", "union", parts)

        def inside(x, chord=chord, segs=segs):
            ins = chord is not None and plane.even_odd_inside([chord], x)
            for a, b, c, r, mid, out in segs:
                n = np.array([a[1] - b[1], b[0] - a[0]])
                if np.linalg.norm(x - c) <= r and ((x - a) @ n > 0) == ((mid - a) @ n > 0):
                    ins = out
            return ins

        probe = path[0][1][2] if path[0][1] is not None else (pts[0] + pts[1 % len(pts)]) / 2
        regions.append((tree, inside, probe))
    m = len(regions)
    holders = [[p for p in range(m) if p != q and regions[p][1](regions[q][2])] for q in range(m)]
    depth = [len(h) for h in holders]
    out = []
    for p in range(m):
        if depth[p] % 2:
            continue
        inner = [regions[q][0] for q in range(m) if depth[q] == depth[p] + 1 and p in holders[q]]
        out.append(regions[p][0] if not inner else ("op", "difference", [regions[p][0]] + inner))
    if not out:
        return None
    extra = ("drawing", paths, circles)
    return ("op", "union", out, extra) if len(out) > 1 else ("op", "union", out + [out[0]], extra) if out[0][0] == "op" else out[0]
