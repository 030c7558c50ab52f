"""import(): a DXF drawing as OpenSCAD 2021.01 reads it (src/dxfdata.cc), parsed
by ezdxf; meshes and surface() height maps."""

import math
import os
from fractions import Fraction
import re

import numpy as np

from . import meaning
from . import plane
from . import svg

__all__ = ['DXF_GRID', 'drawing_tree', 'dxf_paths', 'dxf_pieces', 'import_2d', 'import_mesh', 'merged', 'surface_mesh']


# --------------------------------------------------------------------------
# import(): a DXF drawing as OpenSCAD 2021.01 reads it (src/dxfdata.cc),
# parsed by ezdxf: LINE, LWPOLYLINE, ARC, CIRCLE, ELLIPSE and INSERT entities
# of the layer, points moved by -origin and scaled, pieces joined into paths
# where their ends meet on OpenSCAD's coarse grid of 2^-10 (open chains
# first, each closed by a straight edge, then the rest: a chain that stops
# away from its start loses one end), all paths filled together even-odd.
# Curves stay curves, or are cut into OpenSCAD's fragments for an explicit
# $fn of 3 to 8.
# --------------------------------------------------------------------------

DXF_GRID = 2.0**-10


def dxf_pieces(path, layer, origin, scale, fragments=None):
    """(pieces, ellipses): pieces (a, b, arc) with arc None or (A, c, a
    point of the arc between its ends), the arc on the ellipse c + A (cos w,
    sin w); whole circles and ellipses as (A, c). `fragments`, when given,
    cuts every curve into that many straight pieces a turn."""
    import ezdxf

    doc = ezdxf.readfile(path)
    pieces, ellipses = [], []

    def curve(A, c, w0, w1, m):
        """A curve of the entity's own ellipse (A, c), placed by m (a 2 x 3
        matrix), from w0 to w1 as OpenSCAD reads one."""
        while w0 > w1:
            w1 += 2 * math.pi
        if w1 == w0:
            return
        A, c = m[:, :2] @ A, m[:, :2] @ c + m[:, 2]
        at = lambda w: c + A @ np.array([math.cos(w), math.sin(w)])
        if fragments:
            k = int(math.ceil(fragments * (w1 - w0) / (2 * math.pi)))
            ws = [w0 + (w1 - w0) * i / k for i in range(k + 1)]
            pieces.extend((at(ws[i]), at(ws[i + 1]), None) for i in range(k))
        elif w1 - w0 >= 2 * math.pi:
            ellipses.append((A, c))
        else:
            pieces.append((at(w0), at(w1), (A, c, at((w0 + w1) / 2))))

    def add(e, m):
        t = e.dxftype()
        pt = lambda p: m[:, :2] @ np.array([p[0], p[1]], float) + m[:, 2]
        if t == "LINE":
            pieces.append((pt(e.dxf.start), pt(e.dxf.end), None))
        elif t == "LWPOLYLINE":
            v = [pt(p) for p in e.get_points("xy")]
            pieces.extend((v[i], v[i + 1], None) for i in range(len(v) - 1))
            if e.closed and len(v) > 1:
                pieces.append((v[-1], v[0], None))
        elif t == "CIRCLE":
            curve(e.dxf.radius * np.eye(2), np.array([e.dxf.center[0], e.dxf.center[1]], float), 0.0, 2 * math.pi, m)
        elif t == "ARC":
            curve(e.dxf.radius * np.eye(2), np.array([e.dxf.center[0], e.dxf.center[1]], float), math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle), m)
        elif t == "ELLIPSE":
            u = np.array([e.dxf.major_axis[0], e.dxf.major_axis[1]], float)
            A = np.column_stack([u, e.dxf.ratio * np.array([-u[1], u[0]])])
            curve(A, np.array([e.dxf.center[0], e.dxf.center[1]], float), e.dxf.start_param, e.dxf.end_param, m)

    # (p - origin) * scale, as a 2 x 3 matrix.
    place = np.array([[scale, 0.0, -origin[0] * scale], [0.0, scale, -origin[1] * scale]])
    for e in doc.modelspace():
        if layer and e.dxf.layer != layer:
            continue
        if e.dxftype() == "INSERT":
            blk = doc.blocks.get(e.dxf.name)
            if blk is None:
                continue
            a = math.radians(e.dxf.rotation)
            turn = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
            lin = scale * turn @ np.diag([e.dxf.xscale, e.dxf.yscale])
            at = place[:, :2] @ np.array([e.dxf.insert[0], e.dxf.insert[1]], float) + place[:, 2]
            for be in blk:
                add(be, np.column_stack([lin, at]))
            continue
        add(e, place)
    return pieces, ellipses


def dxf_paths(pieces):
    """Paths [(point, arc or None)] from pieces joined at their ends, as
    OpenSCAD's DxfData joins its lines, and how many did not close."""
    pts, keys = [], {}

    def key(p):
        i, j = round(p[0] / DXF_GRID), round(p[1] / DXF_GRID)
        if (i, j) in keys:
            return keys[(i, j)]
        # Grid2d::align: the nearest occupied neighbour cell (by steps).
        near = [(abs(di) + abs(dj), keys[(i + di, j + dj)]) for di in (-1, 0, 1) for dj in (-1, 0, 1) if (i + di, j + dj) in keys]
        if near:
            return min(near, key=lambda x: x[0])[1]
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
    # Open chains: the lowest piece with an end no other piece left reaches,
    # scanning again from the start after each.
    while True:
        found = None
        for i in range(len(pieces)):
            if used[i]:
                continue
            for end in ends[i]:
                if all(k == i or used[k] for k in at[end]):
                    found = (i, end)
                    break
            if found:
                break
        if not found:
            break
        chain, last = walk(*found)
        n_open += 1
        paths.append(as_path(chain) + [(pts[last], None)])
    turn = n_open == 0
    for i in range(len(pieces)):
        if used[i]:
            continue
        chain, last = walk(i, ends[i][0])
        path = as_path(chain)
        if last != ends[i][0]:
            # toPolygon2d leaves out the first point, after
            # fixup_path_direction may have turned the path round.
            n_open += 1
            path = path + [(pts[last], None)]
            if turn and turned([p for p, _ in path]):
                path = path[:-2] + [(path[-2][0], None)]
            else:
                path = path[1:-1] + [(path[-1][0], None)]
        paths.append(path)
    return paths, n_open


def turned(ps):
    """Whether OpenSCAD's fixup_path_direction reverses a path with these
    points: at the first point of least x, atan2(dx, dy) of the step back
    below that of the step on."""
    n, b = len(ps), 0
    for j, p in enumerate(ps):
        if p[0] < ps[b][0]:
            b = j
    a = n - 2 if b == 0 else b - 1
    c = 1 if b == n - 1 else b + 1
    u, v = ps[a] - ps[b], ps[c] - ps[b]
    return math.atan2(u[0], u[1]) < math.atan2(v[0], v[1])


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
        # CGAL's header: [ST][C][N][4][n]OFF; a point's coordinates first
        # (a homogeneous fourth with 4), then what is not read.
        kind = re.fullmatch(r"(ST)?(C)?(N)?(4)?(n)?OFF", head[0])
        four = bool(kind and kind.group(4))
        if kind:
            head = head[1:] or words.pop(0)
            if kind.group(5):
                if head[0] != "3":
                    raise rd.err(s, "an nOFF file of another dimension than 3")
                head = head[1:] or words.pop(0)
        nv, nf = int(head[0]), int(head[1])
        xyzw = np.array([w[:4] if four else w[:3] + ["1"] for w in words[:nv]], dtype=float)
        pts = xyzw[:, :3] / xyzw[:, 3:]
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
    elif ext == "nef3":
        pts, faces = nef3_triangles(data.decode())
    else:
        raise rd.err(s, f"import of .{ext} is not in the oracle")
    return merged(pts, faces)


def nef3_triangles(text):
    """The boundary of a CGAL Nef complex (its `Selective Nef Complex` text)
    as triangles: each pair of twin facets whose volumes differ in mark is
    a face; its cycles, walked along each shalfedge's `next` at the vertex
    of its source halfedge, are filled even-odd (manifold3d's triangulator,
    holes turned) in the plane across the facet's largest normal component,
    the
    triangles' corners its vertices."""
    import manifold3d as mf

    lines = [ln.strip() for ln in text.splitlines()]
    counts = [int(lines[2 + k].split()[1]) for k in range(7)]
    at, recs = 9, []
    for c in counts:
        rows = []
        for ln in lines[at : at + c]:
            inner = ln[ln.index("{") + 1 : ln.rindex("}")]
            head, _, tail = inner.partition("|")
            rows.append(([f.split() for f in head.split(",")], [float(Fraction(w)) for w in tail.split()], ln[ln.rindex("}") + 1 :].strip() == "1"))
        recs.append(rows)
        at += c
    verts, hedges, facets, volumes, sedges = recs[:5]
    point = np.array([np.array(t[:3]) / t[3] for _, t, _ in verts])
    vertex_of = [int(f[1][0]) for f, _, _ in hedges]
    inside = [m for _, _, m in volumes]
    tris = []
    for i, (f, pl, _) in enumerate(facets):
        twin = int(f[0][0])
        if twin < i or inside[int(f[-1][0])] == inside[int(facets[twin][0][-1][0])]:
            continue
        k = int(np.argmax(np.abs(pl[:3])))
        keep = [j for j in range(3) if j != k]
        loops, corner = [], {}
        for start in f[1]:
            e, loop = int(start), []
            while True:
                p3 = point[vertex_of[int(sedges[e][0][3][0])]]
                loop.append(p3[keep].tolist())
                corner[tuple(p3[keep])] = p3
                e = int(sedges[e][0][6][0])
                if e == int(start):
                    break
            loops.append(loop)
        # Even-odd: a loop inside an odd number of others is a hole, turned
        # clockwise, the others counter-clockwise, as manifold3d fills them.
        arrs = [np.array(l) for l in loops]
        for j, l in enumerate(arrs):
            probe = l.mean(axis=0) if len(l) == 3 else l[0]
            depth = sum(plane.even_odd_inside([o], probe) for m, o in enumerate(arrs) if m != j)
            area = np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1])
            if (area > 0) == (depth % 2 == 1):
                arrs[j] = l[::-1]
        flat = np.concatenate(arrs)
        for t in np.asarray(mf.triangulate([a.tolist() for a in arrs])):
            q = np.zeros((3, 3))
            for j in range(3):
                q[j] = corner[tuple(flat[t[j]])]
            # Facing out: along the plane's normal when this side of the
            # facet is the outside volume, against it otherwise.
            out = np.array(pl[:3]) * (1.0 if not inside[int(f[-1][0])] else -1.0)
            if np.cross(q[1] - q[0], q[2] - q[0]) @ out < 0:
                q = q[::-1]
            tris.append(q)
    pts = np.concatenate(tris) if tris else np.zeros((0, 3))
    return pts, np.arange(len(pts)).reshape(-1, 3).tolist()


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
    fn = a.get("$fn", 0.0)
    fragments = int(max(fn, 3.0)) if 0 < fn < 9 else None
    scale = meaning.num(rd.path, s, a, "scale", 1.0)
    pieces, ellipses = dxf_pieces(path, a.get("layer", a.get("layername", "")) or "", origin, scale, fragments)
    paths, _ = dxf_paths(pieces)
    # A single arc closing on itself is a whole ellipse.
    ellipses += [path[0][1][:2] for path in paths if len(path) == 1 and path[0][1] is not None]
    keep = [p for p in paths if len(p) >= 3 or (len(p) == 2 and any(x is not None for _, x in p))]
    return drawing_tree(keep, ellipses)


def drawing_tree(paths, ellipses):
    """A drawing as the oracle's 2-D tree, filled even-odd: the parity
    ("xor") of all its paths' polygons of chords, each arc's segment (the
    ellipse cut by the chord's half-plane on the arc's side) and each whole
    ellipse. A 4th element carries the paths and ellipses for the oracle's
    own mesh."""
    parts, loops = [], []
    for path in paths:
        pts = [p for p, _ in path]
        if len(pts) >= 3:
            loops.append(np.array(pts))
        for i, (a, arc) in enumerate(path):
            if arc is None:
                continue
            b = path[(i + 1) % len(path)][0]
            A, c, mid = arc
            t = (b - a) / np.linalg.norm(b - a)
            n = np.array([-t[1], t[0]])
            if (mid - a) @ n < 0:
                n = -n
            d = np.linalg.norm(c - a) + np.abs(A).sum() + np.linalg.norm(b - a)
            rect = np.array([a - d * t, b + d * t, b + d * t + d * n, a - d * t + d * n])
            parts.append(("op", "intersection", [("ellipse", A, c), ("poly", [rect])]))
    parts += [("ellipse", A, c) for A, c in ellipses]
    if loops:
        parts.insert(0, ("poly", loops))
    if not parts:
        return None
    extra = ("drawing", paths, ellipses)
    return ("op", "xor", parts, extra) if len(parts) > 1 else ("op", "union", parts + parts, extra)
