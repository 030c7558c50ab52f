"""Meaning: each statement read as OpenSCAD means it, into the scene's tree of
leaves under operations; read() is the entry point."""

import math

import numpy as np

from . import bounds
from . import display_list
from . import dxf
from . import plane
from . import solids
from . import syntax
from . import text

__all__ = ['BACKGROUND', 'CORNFIELD', 'EXTRUSIONS', 'Leaf', 'Op', 'PARAMS', 'Reader', 'SCENE', 'SHAPES_2D', 'SOLIDS', 'Scene', 'TRANSFORMS', 'affine', 'axis_rotation', 'bind', 'default_lights', 'srgb_decode', 'srgb_encode', 'num', 'read', 'sin_cos_deg', 'union_leaves', 'vec']


# --------------------------------------------------------------------------
# Meaning
# --------------------------------------------------------------------------

CORNFIELD = dict(
    color=np.array([249, 215, 44]) / 255.0, ka=0.2, kd=0.8, ks=0.3, ns=30.0, kr=0.0, kt=0.0, ior=1.5
)
BACKGROUND = np.array([1.0, 1.0, 0.898])


def srgb_decode(c):
    """IEC 61966-2-1: an sRGB-encoded value (as files give colours) as a
    linear one; docs/LANGUAGE.md says csgrt shades in linear values."""
    c = np.asarray(c, dtype=float)
    a = np.abs(c)
    return np.sign(c) * np.where(a <= 0.04045, a / 12.92, ((a + 0.055) / 1.055) ** 2.4)


def srgb_encode(x):
    """A linear value in [0, 1] as sRGB (the 8-bit image holds these)."""
    x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def default_lights(view):
    """csgrt's rig where a scene gives no lights (docs/LANGUAGE.md), placed
    about the camera view = (eye, lookat, up, fov): ambient 1; a key of 0.85
    from (-0.5, 0.5, 0.7) in the camera's (right, up, back) axes, casting
    shadows; shadowless lights of 0.15 from (0.9, -0.1, 0.45) and 0.25 from
    (0, 1, 0.2). Tuples (kind, colour, x, shadows)."""
    eye, lookat, up, _ = view

    def unit(v):
        v = np.array(v, dtype=float)
        return v / np.linalg.norm(v)

    fwd = unit(np.asarray(lookat, float) - np.asarray(eye, float))
    right = unit(np.cross(fwd, up))
    upv = np.cross(right, fwd)

    def travel(i, r, u, b, shadows):
        return ("directional", np.full(3, i), -unit(r * right + u * upv - b * fwd), shadows)

    return [
        ("ambient", np.ones(3), None, False),
        travel(0.85, -0.5, 0.5, 0.7, True),
        travel(0.15, 0.9, -0.1, 0.45, False),
        travel(0.25, 0.0, 1.0, 0.2, False),
    ]


PARAMS = {
    "cube": ["size", "center"],
    "sphere": ["r", "d"],
    "cylinder": ["h", "r1", "r2", "center", "r", "d", "d1", "d2"],
    "torus": ["R", "r"],
    "polyhedron": ["points", "faces", "convexity", "triangles"],
    "surface": ["file", "center", "invert", "convexity", "timestamp"],
    "halfspace": ["normal", "offset"],
    "square": ["size", "center"],
    "circle": ["r", "d"],
    "polygon": ["points", "paths", "convexity"],
    "offset": ["r", "delta", "chamfer"],
    "projection": ["cut", "convexity"],
    "resize": ["newsize", "auto", "convexity"],
    "hull": [],
    "minkowski": ["convexity"],
    "import": ["file", "layer", "convexity", "origin", "scale", "width", "height", "filename", "layername", "center", "dpi", "id", "timestamp"],
    "text": ["text", "size", "font", "halign", "valign", "spacing", "direction", "language", "script"],
    "linear_extrude": ["height", "center", "convexity", "twist", "slices", "scale", "file", "layer", "origin", "timestamp"],
    "rotate_extrude": ["angle", "convexity", "file", "layer", "origin", "scale", "timestamp"],
    "translate": ["v"],
    "rotate": ["a", "v"],
    "scale": ["v"],
    "mirror": ["v"],
    "multmatrix": ["m"],
    "color": ["c", "alpha"],
    "material": ["color", "ka", "kd", "ks", "ns", "kr", "kt", "ior"],
    "union": [],
    "intersection": [],
    "difference": [],
    "group": [],
    "render": ["convexity"],
    "camera": ["eye", "lookat", "up", "fov"],
    "background": ["color"],
    "ambient_light": ["color"],
    "directional_light": ["color", "direction", "shadows"],
    "point_light": ["color", "position"],
}
SOLIDS = ("cube", "sphere", "cylinder", "torus", "halfspace", "polyhedron", "surface")
SHAPES_2D = ("square", "circle", "polygon", "text", "import")
EXTRUSIONS = ("linear_extrude", "rotate_extrude")
TRANSFORMS = ("translate", "rotate", "scale", "mirror", "multmatrix")
SCENE = ("camera", "background", "ambient_light", "directional_light", "point_light")


class Leaf:
    """A primitive in its OpenSCAD coordinates, placed by `matrix`."""

    def __init__(self, kind, params, matrix, material, stmt):
        self.kind, self.params, self.matrix, self.material = kind, params, matrix, material
        self.line, self.col = stmt.line, stmt.col
        self.stmt = stmt
        self.id = None


class Op:
    def __init__(self, op, children):
        self.op, self.children = op, children


def union_leaves(rd, s, node):
    """The leaves of a 3-D tree of unions (for hull and minkowski); an
    intersection or a difference is not in the oracle there."""
    if node is None:
        return []
    if isinstance(node, Op):
        if node.op != "union":
            raise rd.err(s, f"{s.name} of a 3-D {node.op} is not in the oracle")
        return [x for c in node.children for x in union_leaves(rd, s, c)]
    if node.kind == "halfspace":
        raise rd.err(s, f"{s.name} of a halfspace is not in the oracle")
    return [node]


class Scene:
    def __init__(self):
        self.root = None
        self.camera = None  # (eye, lookat, up, fov) as the file says
        self.background = BACKGROUND
        self.lights = []
        self.leaves = []

    def view(self, width, height, framed=None):
        """(eye, lookat, up, fov) to render at width x height: the file's
        camera, else the framing of `framed` (the box csgrt says its
        default camera framed, checked by the oracle against its own mesh)
        or, without it, of the tree's box."""
        return self.camera if self.camera else bounds.framing(self, width, height, framed)

    def lights_seen_by(self, view):
        """The lights of a picture taken from view: the file's, or the
        default rig about that camera."""
        return self.lights if self.lights else default_lights(view)


def bind(path, s):
    """The statement's arguments by name ($-variables are OpenSCAD's
    facet settings; an explicit $fn of 3 to 8 on a circle or cylinder is a
    shape, on a sphere one the oracle cannot build yet)."""
    names = PARAMS[s.name]
    out, k = {}, 0
    for key, v in s.args:
        if key is None:
            if k >= len(names):
                raise syntax.ReadError(path, s.line, s.col, f"too many arguments for {s.name}")
            key = names[k]
            k += 1
        elif key.startswith("$"):
            if key == "$fn" and isinstance(v, float):
                out["$fn"] = v
            continue
        elif key not in names:
            raise syntax.ReadError(path, s.line, s.col, f"unknown argument {key} for {s.name}")
        if v is not syntax.UNDEF:
            out[key] = v
    return out


def num(path, s, a, key, default=None):
    v = a.get(key, default)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, float) or not math.isfinite(v):
        raise syntax.ReadError(path, s.line, s.col, f"{key} of {s.name} must be a finite number")
    return v


def vec(path, s, a, key, default=None, scalar=False, sizes=(3,)):
    v = a.get(key, default)
    if v is None:
        return None
    if scalar and isinstance(v, float):
        return np.full(3, v)
    if (
        not isinstance(v, list)
        or len(v) not in sizes
        or not all(isinstance(x, float) and not isinstance(x, bool) and math.isfinite(x) for x in v)
    ):
        raise syntax.ReadError(path, s.line, s.col, f"{key} of {s.name} must be a vector of {sizes} numbers")
    return np.array(v + [0.0] * (3 - len(v)) if len(v) < 3 else v, dtype=float)


def sin_cos_deg(deg):
    """sin and cos of degrees, exact at multiples of 90 (as OpenSCAD)."""
    r = math.fmod(deg, 360.0)
    if r < 0:
        r += 360.0
    if r % 90.0 == 0.0:
        return [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)][int(r // 90) % 4]
    return math.sin(math.radians(r)), math.cos(math.radians(r))


def axis_rotation(axis, deg):
    """Rodrigues: right-handed turn by deg about the unit axis."""
    s, c = sin_cos_deg(deg)
    x, y, z = axis
    t = 1 - c
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ]
    )


def affine(m3=None, t=None):
    m = np.eye(4)
    if m3 is not None:
        m[:3, :3] = m3
    if t is not None:
        m[:3, 3] = t
    return m


class Reader:
    def __init__(self, path):
        self.path = path
        self.scene = Scene()
        self.subtracted = False

    def err(self, s, msg):
        return syntax.ReadError(self.path, s.line, s.col, msg)

    def top(self, stmts):
        roots = [s for s in self.walk_bang(stmts)]
        if roots:
            stmts_used = [roots[0]]
        else:
            stmts_used = stmts
        kids = []
        for s in stmts:
            if s.name in SCENE:
                if s.mods:
                    raise self.err(s, "a scene statement takes no modifiers")
                self.scene_statement(s)
        for s in plane.operands([s for s in stmts_used if s.name not in SCENE]):
            if s is None:
                continue
            n = self.node(s, np.eye(4), dict(CORNFIELD))
            if n is not None:
                kids.append(n)
        self.scene.root = self.union(kids)

    def walk_bang(self, stmts):
        for s in stmts:
            if "*" in s.mods or "%" in s.mods:
                continue
            if "!" in s.mods:
                yield s
            yield from self.walk_bang(s.children)

    @staticmethod
    def union(kids):
        if not kids:
            return None
        return kids[0] if len(kids) == 1 else Op("union", kids)

    def node(self, s, xf, mat, bang_ok=True):
        if "%" in s.mods or "*" in s.mods:
            return None
        name = s.name
        if name in SCENE:
            raise self.err(s, f"{name} must stand at the top level")
        if name not in PARAMS:
            raise self.err(s, f"the oracle does not know {name}")
        a = bind(self.path, s)
        if name in SOLIDS:
            if s.children:
                raise self.err(s, f"{name} takes no children")
            return self.solid(s, a, xf, mat)
        if name == "resize" and not plane.flat_stmt(s):
            return self.resize(s, a, xf, mat)
        if name == "import" and not plane.flat_stmt(s):
            if s.children:
                raise self.err(s, "import takes no children")
            pts, faces = dxf.import_mesh(self, s, a)
            return self.leaf(s, "polyhedron", dict(points=pts, faces=faces), xf, mat)
        kids = lambda x, m: [k for k in (self.node(c, x, m) for c in plane.operands(s.children) if c is not None) if k is not None]
        if name in ("hull", "minkowski") and not plane.flat_stmt(s):
            # Its children's leaves, read in place and kept out of the
            # scene's: one leaf of its own, meshed by manifold's hull or
            # Minkowski sum of theirs.
            n0 = len(self.scene.leaves)
            if name == "hull":
                parts = union_leaves(self, s, self.union(kids(xf, mat)))
                params = dict(parts=parts)
            else:
                live = [c for c in plane.operands(s.children) if c is not None]
                # The sum moves once: the first operand under the whole
                # transform, the others under its linear part.
                lin = xf.copy()
                lin[:3, 3] = 0.0
                ops = [union_leaves(self, s, self.node(c, xf if i == 0 else lin, mat)) for i, c in enumerate(live)]
                params = dict(operands=[o for o in ops if o])
            del self.scene.leaves[n0:]
            if not params.get("parts", params.get("operands")):
                return None
            return self.leaf(s, name, params, np.eye(4), mat)
        if name in SHAPES_2D or name in ("projection", "resize", "hull", "minkowski", "offset"):
            # OpenSCAD's preview of a 2-D shape among solids: a slab 1 thick
            # centred on its plane, 1.1 when subtracted.
            f = self.sections_out(s, self.flat(s, np.eye(3)))
            if f is None:
                return None
            h = 1.1 if self.subtracted else 1.0
            return self.leaf(s, "linear_extrude", dict(flat=f[0], frame=f[1], h=h, z0=-h / 2, scale=1.0), xf, mat)
        if name in EXTRUSIONS:
            return self.extrusion(s, a, xf, mat)
        if name in TRANSFORMS:
            return self.union(kids(xf @ self.transform(s, a), mat))
        if name in ("color", "material"):
            return self.union(kids(xf, self.appearance(s, a, mat)))
        if name == "intersection":
            parts = [None if c is None else self.node(c, xf, mat) for c in plane.operands(s.children)]
            if not parts or any(p is None for p in parts):
                return None
            return parts[0] if len(parts) == 1 else Op("intersection", parts)
        if name == "difference":
            live = plane.operands(s.children)
            if not live or live[0] is None:
                return None
            live = [c for c in live if c is not None]
            first = self.node(live[0], xf, mat)
            if first is None:
                return None
            self.subtracted = not self.subtracted
            rest = [k for k in (self.node(c, xf, mat) for c in live[1:]) if k is not None]
            self.subtracted = not self.subtracted
            return first if not rest else Op("difference", [first, self.union(rest)])
        return self.union(kids(xf, mat))  # union, group, render

    def leaf(self, s, kind, params, xf, mat):
        if abs(np.linalg.det(xf[:3, :3])) <= 1e-300 or np.linalg.cond(xf[:3, :3]) > 1e15:
            return None  # flattened: no volume
        leaf = Leaf(kind, params, xf, dict(mat), s)
        leaf.id = len(self.scene.leaves)
        self.scene.leaves.append(leaf)
        return leaf

    def solid(self, s, a, xf, mat):
        k = s.name
        if k == "surface":
            pts, faces = dxf.surface_mesh(self, s, a)
            if pts is None:
                return None
            return self.leaf(s, "polyhedron", dict(points=pts, faces=faces), xf, mat)
        if k == "polyhedron":
            pts = a.get("points")
            faces = a.get("faces", a.get("triangles"))
            if pts is None or pts == [] or faces is None or faces == []:
                # (nothing, in OpenSCAD: a function that found none)
                return None
            if not isinstance(pts, list) or any(not isinstance(p, list) or len(p) != 3 for p in pts):
                raise self.err(s, "points of polyhedron must be a list of 3-D points")
            pts = np.array(pts, dtype=float)
            if not isinstance(faces, list):
                raise self.err(s, "polyhedron needs faces")
            out = []
            for f in faces:
                # OpenSCAD 2021.01 drops an index out of range from its face
                # (cut to a whole number first) and a face left with fewer
                # than 3 points.
                idx = [int(math.trunc(i)) for i in f if isinstance(i, float) and 0 <= math.trunc(i) < len(pts)]
                if len(idx) >= 3:
                    out.append(idx)
            return self.leaf(s, k, dict(points=pts, faces=out), xf, mat)
        if k == "cube":
            size = vec(self.path, s, a, "size", 1.0, scalar=True)
            center = bool(a.get("center", False))
            if size.min() <= 0:
                return None
            return self.leaf(s, k, dict(size=size, center=center), xf, mat)
        if k == "sphere":
            d = num(self.path, s, a, "d")
            r = d / 2 if d is not None else num(self.path, s, a, "r", 1.0)
            if r <= 0:
                return None
            fn = a.get("$fn", 0.0)
            if 0 < fn < 9:
                # OpenSCAD's ring polyhedron (primitives.cc): (n + 1) // 2
                # rings at phi = 180 (i + 1/2) / rings, n points each; caps
                # and bands of triangles.
                n = int(max(fn, 3.0))
                rings = (n + 1) // 2
                pts = []
                for i in range(rings):
                    sp, cp = sin_cos_deg(180.0 * (i + 0.5) / rings)
                    for j in range(n):
                        sa, ca = sin_cos_deg(360.0 * j / n)
                        pts.append([r * sp * ca, r * sp * sa, r * cp])
                faces = [list(range(n))] + [list(range((rings - 1) * n, rings * n))[::-1]]
                for i in range(rings - 1):
                    for j in range(n):
                        a0, a1 = i * n + j, i * n + (j + 1) % n
                        faces += [[a0 + n, a1 + n, a0], [a1 + n, a1, a0]]
                return self.leaf(s, "polyhedron", dict(points=np.array(pts), faces=faces), xf, mat)
            return self.leaf(s, k, dict(r=r), xf, mat)
        if k == "cylinder":
            g = lambda key: num(self.path, s, a, key)
            h = g("h") if g("h") is not None else 1.0
            r = g("d") / 2 if g("d") is not None else (g("r") if g("r") is not None else 1.0)
            r1 = g("d1") / 2 if g("d1") is not None else (g("r1") if g("r1") is not None else r)
            r2 = g("d2") / 2 if g("d2") is not None else (g("r2") if g("r2") is not None else r)
            if min(r1, r2) < 0:
                raise self.err(s, "a radius of cylinder is negative")
            if h <= 0 or max(r1, r2) <= 0:
                return None
            center = bool(a.get("center", False))
            fn = a.get("$fn", 0.0)
            if 0 < fn < 9:
                # OpenSCAD's frustum over the regular n-gon (vertex i at
                # 360 i / n): the extrusion of the wider end's n-gon,
                # tapered to the other end, flipped end for end when the
                # top is the wider.
                n_ = int(max(fn, 3.0))
                rmax = max(r1, r2)
                sc = [sin_cos_deg(360.0 * i / n_) for i in range(n_)]
                poly = ("poly", [np.array([[rmax * c, rmax * si] for si, c in sc])])
                z0 = -h / 2 if center else 0.0
                flip = np.eye(4)
                if r1 < r2:
                    flip[2, 2], flip[2, 3] = -1.0, 2 * z0 + h
                return self.leaf(s, "linear_extrude", dict(flat=poly, h=h, z0=z0, scale=min(r1, r2) / rmax), xf @ flip, mat)
            return self.leaf(s, k, dict(h=h, r1=r1, r2=r2, center=center), xf, mat)
        if k == "torus":
            R = num(self.path, s, a, "R", 2.0)
            r = num(self.path, s, a, "r", 0.5)
            if R < 0 or r < 0:
                raise self.err(s, "a radius of torus is negative")
            if R == 0 or r == 0:
                return None
            if r >= R:
                raise self.err(s, "the tube radius r of a torus must be smaller than R")
            return self.leaf(s, k, dict(R=R, r=r), xf, mat)
        n = vec(self.path, s, a, "normal", [0.0, 0.0, 1.0])
        if not np.any(n):
            raise self.err(s, "the normal of a halfspace must not be zero")
        return self.leaf(s, k, dict(normal=n, offset=num(self.path, s, a, "offset", 0.0)), xf, mat)

    # ---------------------------------------------------------------- 2-D

    def flat(self, s, m):
        """A 2-D statement under the plane matrix m (3x3, homogeneous) as a
        tree: ("poly", [loops as (k, 2) arrays]) filled even-odd,
        ("curves", [loops]) the same with curved edges (a loop a list of
        (point, control) pairs, the edge from each point to the next a line
        when control is None, else the quadratic Bézier through it: a
        glyph),
        ("ellipse", A, c) the image of the unit disc under x -> A x + c,
        ("op", name, kids); None when empty."""
        if "%" in s.mods or "*" in s.mods:
            return None
        name = s.name
        if name not in PARAMS or name in SCENE:
            raise self.err(s, f"{name} cannot stand in a 2-D shape")
        if plane.dimension(s) is False:
            # A solid in a 2-D operation is left out (OpenSCAD's render).
            return None
        a = bind(self.path, s)
        if name in SHAPES_2D:
            return self.shape_2d(s, a, m)
        if name in TRANSFORMS:
            t = self.transform(s, a)
            # OpenSCAD keeps the rows and columns of x, y and 1.
            t2 = t[np.ix_([0, 1, 3], [0, 1, 3])]
            if np.linalg.det(t2[:2, :2]) == 0:
                return None
            return self.flat_kids(s, "union", m @ t2)
        if name in ("color", "material"):
            self.appearance(s, a, dict(CORNFIELD))
            return self.flat_kids(s, "union", m)
        if name == "offset":
            return self.offset(s, a, m)
        if name == "resize":
            newsize, auto = solids.resize_args(self, s, a)
            child = self.flat_kids(s, "union", np.eye(3))
            if child is None:
                return None
            size = [0.0, 0.0]
            for i in range(2):
                if newsize[i] > 0 or auto[i]:
                    lo, hi = solids.flat_extent_exact(self, s, child, i)
                    size[i] = hi - lo
            # Polygon2d::resize
            maxdim = 1 if newsize[1] and newsize[1] > newsize[0] else 0
            sc = [newsize[i] / size[i] if newsize[i] > 0 else 1.0 for i in range(2)]
            autoscale = newsize[maxdim] / size[maxdim] if newsize[maxdim] > 0 else 1.0
            k = [sc[i] if not auto[i] or newsize[i] > 0 else autoscale for i in range(2)]
            return plane.flat_moved(child, m @ np.diag([k[0], k[1], 1.0]))
        if name == "projection":
            # The children as solids, kept out of the scene's leaves: read
            # again, exactly, when the slice (or shadow) is extruded.
            n0 = len(self.scene.leaves)
            node = self.union([k for k in (self.node(c, np.eye(4), dict(CORNFIELD)) for c in s.children) if k is not None])
            del self.scene.leaves[n0:]
            kind = "section" if a.get("cut", False) is True else "shadow"
            return None if node is None else (kind, node, m, s)
        if name == "minkowski":
            # Summed in its own frame, then placed (the sum moves once).
            live = [c for c in s.children if not ("%" in c.mods or "*" in c.mods)]
            kids = [self.flat(c, np.eye(3)) for c in live]
            # An empty operand empties the sum.
            if not kids or any(k is None for k in kids):
                return None
            try:
                return plane.minkowski_flat(kids, m)
            except ValueError as e:
                raise self.err(s, str(e))
        op = name if name in ("intersection", "difference", "hull") else "union"
        return self.flat_kids(s, op, m)

    def resize(self, s, a, xf, mat):
        """3-D resize: the children's exact box in the resize's frame, then
        CGAL_Nef_polyhedron::resize's scale about the origin. Only a Nef
        polyhedron (a union or CSG operation of two or more, render,
        minkowski) takes a size below 0; PolySet::resize leaves that axis."""
        newsize, auto = solids.resize_args(self, s, a)

        def nef(children):
            live = [c for c in children if not ("%" in c.mods or "*" in c.mods)]
            if len(live) != 1:
                return len(live) > 1
            c = live[0]
            if c.name in ("render", "minkowski"):
                return True
            passes = c.name in TRANSFORMS or c.name in ("color", "material", "group", "union", "difference", "intersection")
            return passes and nef(c.children)

        if not nef(s.children):
            newsize = [max(x, 0.0) for x in newsize]
        n0 = len(self.scene.leaves)
        node = self.union([k for k in (self.node(c, np.eye(4), mat) for c in s.children) if k is not None])
        del self.scene.leaves[n0:]
        if node is None:
            return None
        lo, hi = solids.exact_box(self, s, node)
        size = hi - lo
        scale = [1.0, 1.0, 1.0]
        imax = 0
        for i in range(3):
            if newsize[i]:
                if size[i] == 0:
                    return self.union([k for k in (self.node(c, xf, mat) for c in s.children) if k is not None])
                scale[i] = newsize[i] / size[i]
                if newsize[i] > newsize[imax]:
                    imax = i
        autoscale = newsize[imax] / size[imax] if newsize[imax] else 1.0
        for i in range(3):
            if auto[i] and newsize[i] == 0:
                scale[i] = autoscale
        S = np.diag(scale + [1.0])
        return self.union([k for k in (self.node(c, xf @ S, mat) for c in s.children) if k is not None])

    def sections_out(self, s, f):
        """(exact tree, framing tree) of a 2-D tree: each projection's
        slice computed exactly (see `section_tree`), and in the framing
        tree wrapped as ("framed", slice, lo, hi) with csgrt's box of it —
        the xy box of its children's box; None when empty."""
        if f is None:
            return None
        if f[0] == "shadow":
            _, node, m, st = f
            M = np.eye(4)
            M[np.ix_([0, 1, 3], [0, 1, 3])] = m
            try:
                t = solids.shadow_tree(solids.moved_node(node, M))
            except ValueError as e:
                raise self.err(st, str(e))
            if t is None:
                return None
            lo, hi = solids.flat_box(t)
            return t, ("framed", t, lo, hi)
        if f[0] == "section":
            _, node, m, st = f
            M = np.eye(4)
            M[np.ix_([0, 1, 3], [0, 1, 3])] = m
            moved = solids.moved_node(node, M)
            lo, hi = bounds.box(moved)
            if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
                raise self.err(st, "the projection of an unbounded solid is not in the oracle")
            if lo[2] > 0 or hi[2] < 0 or np.any(lo > hi):
                return None
            size = hi - lo
            big = (lo[:2] - size[:2] - 1.0, hi[:2] + size[:2] + 1.0)
            try:
                t = solids.section_tree(moved, big)
            except ValueError as e:
                raise self.err(st, str(e))
            return None if t is None else (t, ("framed", t, lo[:2], hi[:2]))
        if f[0] != "op":
            return f, f
        parts = [self.sections_out(s, k) for k in f[2]]
        if f[1] == "intersection" and any(p is None for p in parts):
            return None
        if f[1] == "difference" and parts[0] is None:
            return None
        live = [p for p in parts if p is not None]
        if not live:
            return None
        if len(live) == 1:
            return live[0]
        return ("op", f[1], [p[0] for p in live]) + tuple(f[3:]), ("op", f[1], [p[1] for p in live])

    def offset(self, s, a, m):
        """offset(r | delta, chamfer) of the children's union, in its own
        frame, then moved by m: ("op", "union" | "difference", pieces,
        (join, d, child, m)) — the pieces (below) in the plane, and what
        manifold3d's own offset is given in the oracle."""
        if "r" in a:
            join, d = "round", num(self.path, s, a, "r")
        elif "delta" in a:
            d = num(self.path, s, a, "delta")
            join = "square" if a.get("chamfer", False) is True else "miter"
        else:
            join, d = "round", 1.0
        child = self.flat_kids(s, "union", np.eye(3))
        if child is None:
            return None
        if plane.has_section(child):
            raise self.err(s, "an offset of a projection is not in the oracle")
        if d == 0:
            return plane.flat_moved(child, m)
        try:
            pieces = plane.offset_pieces(child, join, d)
        except ValueError as e:
            raise self.err(s, str(e))
        if pieces is None:
            return None
        if pieces[0] != "op":
            return plane.flat_moved(pieces, m)
        if len(pieces) == 4:
            # One curved outline's pieces keep their own mark.
            return ("op", "union", [plane.flat_moved(pieces, m)], (join, d, child, m))
        return ("op", pieces[1], [plane.flat_moved(k, m) for k in pieces[2]], (join, d, child, m))

    def flat_kids(self, s, op, m):
        parts = [self.flat(c, m) for c in s.children if not ("%" in c.mods or "*" in c.mods)]
        if op == "intersection" and any(p is None for p in parts):
            return None
        if op == "difference" and (not parts or parts[0] is None):
            return None
        live = [p for p in parts if p is not None]
        if not live:
            return None
        # (the hull of one shape is still its hull)
        return live[0] if len(live) == 1 and op != "hull" else ("op", op, live)

    def shape_2d(self, s, a, m):
        if s.children:
            raise self.err(s, f"{s.name} takes no children")
        k = s.name
        place = lambda pts: (np.asarray(pts, dtype=float) @ m[:2, :2].T) + m[:2, 2]
        if k == "square":
            v = a.get("size", 1.0)
            size = np.array([v, v]) if isinstance(v, float) else vec(self.path, s, a, "size", sizes=(2,))[:2]
            if size.min() <= 0:
                return None
            lo = -size / 2 if a.get("center", False) else np.zeros(2)
            hi = lo + size
            return ("poly", [place([lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]])])
        if k == "circle":
            d = num(self.path, s, a, "d")
            r = d / 2 if d is not None else num(self.path, s, a, "r", 1.0)
            if r <= 0:
                return None
            fn = a.get("$fn", 0.0)
            if 0 < fn < 9:
                n = int(max(fn, 3.0))
                sc = [sin_cos_deg(360.0 * i / n) for i in range(n)]
                pts = [[r * c, r * si] for si, c in sc]
                return ("poly", [place(pts)])
            return ("ellipse", m[:2, :2] * r, m[:2, 2].copy())
        if k == "text":
            return text.text_2d(self, s, a, place)
        if k == "import":
            f = dxf.import_2d(self, s, a)
            return None if f is None else plane.flat_moved(f, m)
        # OpenSCAD 2021.01 (PolygonNode) leaves out a polygon without
        # points or with a point that is not numbers, and one of fewer than
        # 3 points; it drops an index out of range from its path (a
        # fraction cut to a whole number) and a path left with fewer than 3
        # points adds nothing.
        pts = a.get("points")
        number = lambda x: isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
        if not isinstance(pts, list) or any(not isinstance(p, list) or len(p) != 2 or not all(map(number, p)) for p in pts):
            return None
        pts = np.array(pts, dtype=float).reshape(-1, 2)
        paths = a.get("paths")
        # No paths, or an empty list: all points in order.
        if not paths:
            if len(pts) < 3:
                return None
            paths = [list(range(len(pts)))]
        loops = []
        for path in paths:
            if not isinstance(path, list) or not all(map(number, path)):
                raise self.err(s, "paths of polygon must be lists of indices")
            idx = [int(i) for i in path if 0 <= int(i) < len(pts) and i >= 0]
            # A path on one line has no area (OpenSCAD's sanitizing).
            flat = len(idx) < 3 or np.linalg.matrix_rank(pts[idx] - pts[idx[0]]) < 2
            if not flat:
                loops.append(place(pts[idx]))
        return ("poly", loops) if loops else None

    def extrusion(self, s, a, xf, mat):
        if "file" in a:
            # OpenSCAD 2021.01's deprecated form: the drawing imported, its
            # children ignored; a linear extrusion scales the drawing by
            # the first number of its scale, a turn by its own scale.
            d = {k: a[k] for k in ("file", "layer", "origin", "convexity") if k in a}
            sc = a.get("scale", 1.0)
            d["scale"] = sc[0] if isinstance(sc, list) else sc
            f = dxf.import_2d(self, s, d)
        else:
            f = self.flat_kids(s, "union", np.eye(3))
        if plane.has_section(f):
            if s.name == "rotate_extrude":
                raise self.err(s, "turning a projection is not in the oracle")
            twist = num(self.path, s, a, "twist", 0.0)
            sc = a.get("scale", 1.0)
            if twist != 0 or sc != 1.0 and sc != [1.0, 1.0]:
                raise self.err(s, "a twisted or scaled projection is not in the oracle")
            f = self.sections_out(s, f)
            h = num(self.path, s, a, "height", 100.0)
            if f is None or h <= 0:
                return None
            z0 = -h / 2 if a.get("center", False) else 0.0
            return self.leaf(s, "linear_extrude", dict(flat=f[0], frame=f[1], h=h, z0=z0, scale=1.0), xf, mat)
        if s.name == "linear_extrude":
            twist = num(self.path, s, a, "twist", 0.0)
            h = num(self.path, s, a, "height", 100.0)
            sc = a.get("scale", 1.0)
            sc = [sc, sc] if isinstance(sc, float) else list(vec(self.path, s, a, "scale", sizes=(2,))[:2])
            sc = [max(x, 0.0) for x in sc]
            if f is None or h <= 0:
                return None
            z0 = -h / 2 if a.get("center", False) else 0.0
            if twist != 0.0 or sc[0] != sc[1]:
                # OpenSCAD's slice at height fraction t: x = S(t) R(-twist t) p,
                # S(t) = diag(1 + (sx - 1) t, 1 + (sy - 1) t).
                solids.check_twistable(self, s, f, twist, sc)
                return self.leaf(s, "linear_extrude", dict(flat=f, h=h, z0=z0, scale=None, scale2=sc, twist=twist), xf, mat)
            return self.leaf(s, "linear_extrude", dict(flat=f, h=h, z0=z0, scale=sc[0]), xf, mat)
        angle = num(self.path, s, a, "angle", 360.0)
        if angle <= -360 or angle > 360:
            angle = 360.0
        if f is None or angle == 0:
            return None
        try:
            side = solids.revolve_setup(dict(flat=f))
        except ValueError:
            # OpenSCAD's error: it renders the rest without this.
            return None
        return self.leaf(s, "rotate_extrude", dict(flat=f, angle=angle, side=side), xf, mat)

    def transform(self, s, a):
        k = s.name
        if k == "translate":
            return affine(t=vec(self.path, s, a, "v", [0.0, 0.0, 0.0], sizes=(2, 3)))
        if k == "scale":
            return affine(np.diag(vec(self.path, s, a, "v", 1.0, scalar=True, sizes=(2, 3))))
        if k == "mirror":
            n = vec(self.path, s, a, "v", [0.0, 0.0, 0.0], sizes=(2, 3))
            l2 = float(n @ n)
            return affine(np.eye(3) - 2 * np.outer(n, n) / l2) if l2 else np.eye(4)
        if k == "rotate":
            if "v" in a:
                axis = vec(self.path, s, a, "v")
                if not np.any(axis):
                    raise self.err(s, "the axis of a rotation must not be zero")
                return affine(axis_rotation(axis / np.linalg.norm(axis), num(self.path, s, a, "a", 0.0)))
            ang = a.get("a", 0.0)
            if isinstance(ang, float):
                ang = np.array([0.0, 0.0, ang])
            else:
                ang = vec(self.path, s, a, "a", sizes=(1, 2, 3))
            e = np.eye(3)
            return affine(axis_rotation(e[2], ang[2]) @ axis_rotation(e[1], ang[1]) @ axis_rotation(e[0], ang[0]))
        m = a.get("m")
        if m is None:
            return np.eye(4)
        if not isinstance(m, list) or len(m) not in (3, 4) or any(not isinstance(r, list) or len(r) != 4 for r in m):
            raise self.err(s, "m of multmatrix must be 3 or 4 rows of 4 numbers")
        out = np.eye(4)
        out[: len(m)] = np.array(m, dtype=float)
        if not np.all(np.isfinite(out)):
            raise self.err(s, "m of multmatrix must be finite")
        if len(m) == 4 and list(out[3]) != [0.0, 0.0, 0.0, 1.0]:
            raise self.err(s, "the last row of a multmatrix must be [0, 0, 0, 1]")
        return out

    def appearance(self, s, a, mat):
        m = dict(mat)
        if s.name == "color":
            c = vec(self.path, s, a, "c", sizes=(3, 4)) if "c" in a and len(a["c"]) == 3 else None
            if "c" in a and isinstance(a["c"], list) and len(a["c"]) == 4:
                c4 = [float(x) for x in a["c"]]
                if min(c4) < 0:  # OpenSCAD's "no colour"
                    return m
                c, alpha = np.array(c4[:3]), c4[3]
            else:
                if c is None:
                    return m
                alpha = 1.0
            if "alpha" in a:
                alpha = num(self.path, s, a, "alpha")
            m["color"] = np.clip(c, 0, 1)
            alpha = min(max(alpha, 0.0), 1.0)
            if alpha < 1:
                m["kt"], m["ior"] = 1 - alpha, 1.0
            return m
        if "color" in a:
            m["color"] = vec(self.path, s, a, "color")
        for key in ("ka", "kd", "ks", "ns", "kr", "kt", "ior"):
            v = num(self.path, s, a, key)
            if v is not None:
                if v < 0:
                    raise self.err(s, f"{key} must not be negative")
                m[key] = v
        return m

    def scene_statement(self, s):
        a = bind(self.path, s)
        sc = self.scene
        if s.name == "camera":
            if sc.camera:
                raise self.err(s, "a second camera")
            eye, lookat = vec(self.path, s, a, "eye"), vec(self.path, s, a, "lookat")
            if eye is None or lookat is None:
                raise self.err(s, "a camera needs eye and lookat")
            sc.camera = (eye, lookat, vec(self.path, s, a, "up", [0.0, 0.0, 1.0]), num(self.path, s, a, "fov", 30.0))
        elif s.name == "background":
            sc.background = vec(self.path, s, a, "color")
        else:
            c = vec(self.path, s, a, "color", 1.0, scalar=True)
            if s.name == "ambient_light":
                sc.lights.append(("ambient", c, None, False))
            elif s.name == "directional_light":
                d = vec(self.path, s, a, "direction")
                shadows = a.get("shadows", True)
                if not isinstance(shadows, bool):
                    raise self.err(s, "shadows must be true or false")
                sc.lights.append(("directional", c, d / np.linalg.norm(d), shadows))
            else:
                sc.lights.append(("point", c, vec(self.path, s, a, "position"), True))


def read(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if path.endswith(".ray"):
        return display_list.read_ray(path, text)
    r = Reader(path)
    r.top(syntax.Parser(path, text).file())
    return r.scene
