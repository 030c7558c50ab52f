#!/usr/bin/env python3
"""The oracle's own reader of csgrt scene files (`.csg` and `.ray`).

It shares nothing with csgrt's Rust code: it follows the product contract
(the language reference in the README and OpenSCAD's meaning of each
statement) and builds, in plain Python, what the file says:

* a tree of leaves (sphere, cube, cylinder/cone, torus, halfspace), each in
  its own OpenSCAD coordinates (a cube of `size` from the origin or centred,
  a cylinder from z = 0 to h, ...) with the 4x4 matrix that places it in the
  world and its material, under `union`/`intersection`/`difference` nodes;
* the camera (the file's, or the default framing below), the background and
  the lights.

OpenSCAD's meanings used here: `rotate(a = [x, y, z])` turns about x, then
y, then z (R = Rz Ry Rx); `rotate(a, v)` about the axis v; `rotate(a)`
about z; `mirror(v)` reflects in the plane through the origin with normal v
(a zero v is no mirror); `multmatrix` takes rows; a diameter beats a radius,
`r1`/`r2` beat `r`; `color(c, alpha)`: alpha (or c's fourth entry) below 1
transmits 1 - alpha without bending; OpenSCAD's `color([-1, -1, -1, -1])`
is no colour. `%` and `*` leave a subtree out; `!` renders only that one.
A solid of zero or negative size, or flattened by a singular transform, is
empty.

csgrt's documented defaults: OpenSCAD's Cornfield colours (faces #f9d72c,
background #ffffe5) and, without lights, an ambient term with a key and a
fill light; without a camera, the frame of the scene's box from OpenSCAD's
default view direction (rotation [55, 0, 25]), the eye pulled back until
the box's eight corners lie in the central 90 % of a 30 degree view.

The scene's box, for that framing, is derived here the same way the
README's language reference states it: a leaf's exact world box (an
ellipsoid's or a disc's extent, a torus as circle + ball, a box's corners,
an axis-aligned halfspace bounded on one side), unions join boxes,
intersections cut them, a difference keeps its first child's; when that box
is unbounded (a floor), the union of the bounded leaves' boxes is framed.

Usage as a module: `read(path, width, height)` -> Scene.
"""

import math
import os
import re

import numpy as np
from tools import ROOT

# --------------------------------------------------------------------------
# Errors
# --------------------------------------------------------------------------


class ReadError(Exception):
    def __init__(self, path, line, col, msg):
        super().__init__(f"{path}:{line}:{col}: {msg}")


# --------------------------------------------------------------------------
# The .csg text: tokens and statements
# --------------------------------------------------------------------------

TOKEN = re.compile(
    r"""
    (?P<ws>[ \t\r\n]+)
  | (?P<comment>//[^\n]*|/\*.*?\*/)
  | (?P<number>[-+]?(?:(?:inf|nan)(?![A-Za-z0-9_])|(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?))
  | (?P<string>"(?:[^"\\]|\\.)*")
  | (?P<name>[$A-Za-z_][A-Za-z0-9_]*)
  | (?P<punct>[()\[\]{},;=#%*!])
    """,
    re.VERBOSE | re.DOTALL,
)

UNDEF = object()


class Stmt:
    def __init__(self, name, args, children, mods, line, col):
        self.name, self.args, self.children, self.mods = name, args, children, mods
        self.line, self.col = line, col


class Parser:
    def __init__(self, path, text):
        self.path = path
        self.toks = []
        pos, line, lstart = 0, 1, 0
        while pos < len(text):
            m = TOKEN.match(text, pos)
            if not m:
                raise ReadError(path, line, pos - lstart + 1, f"unexpected character {text[pos]!r}")
            kind = m.lastgroup
            if kind not in ("ws", "comment"):
                self.toks.append((kind, m.group(), line, pos - lstart + 1))
            for k, ch in enumerate(m.group()):
                if ch == "\n":
                    line, lstart = line + 1, pos + k + 1
            pos = m.end()
        self.toks.append(("eof", "", line, pos - lstart + 1))
        self.i = 0

    def peek(self):
        return self.toks[self.i]

    def take(self, value=None, kind=None):
        t = self.toks[self.i]
        if (value is not None and t[1] != value) or (kind is not None and t[0] != kind):
            want = value if value is not None else kind
            raise ReadError(self.path, t[2], t[3], f"expected {want!r}, found {t[1]!r}")
        self.i += 1
        return t

    def file(self):
        out = []
        while self.peek()[0] != "eof":
            if self.peek()[1] == ";":
                self.i += 1
                continue
            out.append(self.statement())
        return out

    def statement(self):
        mods = ""
        while self.peek()[1] in ("#", "%", "*", "!"):
            mods += self.take()[1]
        kind, name, line, col = self.take(kind="name")
        self.take("(")
        args = []
        while self.peek()[1] != ")":
            if self.peek()[0] == "name" and self.toks[self.i + 1][1] == "=":
                key = self.take()[1]
                self.take("=")
                args.append((key, self.value()))
            else:
                args.append((None, self.value()))
            if self.peek()[1] == ",":
                self.i += 1
            elif self.peek()[1] != ")":
                t = self.peek()
                raise ReadError(self.path, t[2], t[3], f"expected ',' or ')', found {t[1]!r}")
        self.take(")")
        children = []
        t = self.peek()
        if t[1] == ";":
            self.i += 1
        elif t[1] == "{":
            self.i += 1
            while self.peek()[1] != "}":
                if self.peek()[1] == ";":
                    self.i += 1
                    continue
                if self.peek()[0] == "eof":
                    raise ReadError(self.path, t[2], t[3], "this block is never closed")
                children.append(self.statement())
            self.i += 1
        else:
            children.append(self.statement())
        return Stmt(name, args, children, mods, line, col)

    def value(self):
        kind, text, line, col = self.peek()
        self.i += 1
        if kind == "number":
            return float(text)
        if kind == "string":
            return re.sub(r"\\(.)", r"\1", text[1:-1])
        if kind == "name" and text in ("true", "false"):
            return text == "true"
        if kind == "name" and text == "undef":
            return UNDEF
        if text == "[":
            out = []
            while self.peek()[1] != "]":
                out.append(self.value())
                if self.peek()[1] == ",":
                    self.i += 1
                elif self.peek()[1] != "]":
                    t = self.peek()
                    raise ReadError(self.path, t[2], t[3], f"expected ',' or ']', found {t[1]!r}")
            self.i += 1
            return out
        raise ReadError(self.path, line, col, f"expected a value, found {text!r}")


# --------------------------------------------------------------------------
# Meaning
# --------------------------------------------------------------------------

CORNFIELD = dict(
    color=np.array([249, 215, 44]) / 255.0, ka=0.2, kd=0.8, ks=0.3, ns=30.0, kr=0.0, kt=0.0, ior=1.5
)
BACKGROUND = np.array([1.0, 1.0, 0.898])


def default_lights():
    def unit(v):
        v = np.array(v, dtype=float)
        return v / np.linalg.norm(v)

    return [
        ("ambient", np.ones(3), None),
        ("directional", np.full(3, 0.8), -unit([-0.35, -0.6, 0.72])),
        ("directional", np.full(3, 0.35), -unit([1.0, -0.25, 0.15])),
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
    "directional_light": ["color", "direction"],
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

    def view(self, width, height):
        """(eye, lookat, up, fov) to render at width x height."""
        return self.camera if self.camera else framing(self, width, height)


def bind(path, s):
    """The statement's arguments by name ($-variables are OpenSCAD's
    facet settings; an explicit $fn of 3 to 8 on a circle or cylinder is a
    shape, on a sphere one the oracle cannot build yet)."""
    names = PARAMS[s.name]
    out, k = {}, 0
    for key, v in s.args:
        if key is None:
            if k >= len(names):
                raise ReadError(path, s.line, s.col, f"too many arguments for {s.name}")
            key = names[k]
            k += 1
        elif key.startswith("$"):
            if key == "$fn" and isinstance(v, float):
                out["$fn"] = v
            continue
        elif key not in names:
            raise ReadError(path, s.line, s.col, f"unknown argument {key} for {s.name}")
        if v is not UNDEF:
            out[key] = v
    return out


def num(path, s, a, key, default=None):
    v = a.get(key, default)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, float) or not math.isfinite(v):
        raise ReadError(path, s.line, s.col, f"{key} of {s.name} must be a finite number")
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
        raise ReadError(path, s.line, s.col, f"{key} of {s.name} must be a vector of {sizes} numbers")
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
        return ReadError(self.path, s.line, s.col, msg)

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
        for s in stmts_used:
            if s.name in SCENE:
                continue
            n = self.node(s, np.eye(4), dict(CORNFIELD))
            if n is not None:
                kids.append(n)
        self.scene.root = self.union(kids)
        if not self.scene.lights:
            self.scene.lights = default_lights()

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
        if name == "resize" and not flat_stmt(s):
            return self.resize(s, a, xf, mat)
        if name == "import" and not flat_stmt(s):
            if s.children:
                raise self.err(s, "import takes no children")
            pts, faces = import_mesh(self, s, a)
            return self.leaf(s, "polyhedron", dict(points=pts, faces=faces), xf, mat)
        kids = lambda x, m: [k for k in (self.node(c, x, m) for c in s.children) if k is not None]
        if name in ("hull", "minkowski") and not flat_stmt(s):
            # Its children's leaves, read in place and kept out of the
            # scene's: one leaf of its own, meshed by manifold's hull or
            # Minkowski sum of theirs.
            n0 = len(self.scene.leaves)
            if name == "hull":
                parts = union_leaves(self, s, self.union(kids(xf, mat)))
                params = dict(parts=parts)
            else:
                live = [c for c in s.children if not ("%" in c.mods or "*" in c.mods)]
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
            parts = [self.node(c, xf, mat) for c in s.children if not ("%" in c.mods or "*" in c.mods)]
            if not parts or any(p is None for p in parts):
                return None
            return parts[0] if len(parts) == 1 else Op("intersection", parts)
        if name == "difference":
            live = [c for c in s.children if not ("%" in c.mods or "*" in c.mods)]
            if not live:
                return None
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
            pts, faces = surface_mesh(self, s, a)
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
        a = bind(self.path, s)
        if name in SOLIDS or name in EXTRUSIONS:
            raise self.err(s, f"{name} is 3-D and cannot stand in a 2-D shape")
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
            newsize, auto = resize_args(self, s, a)
            child = self.flat_kids(s, "union", np.eye(3))
            if child is None:
                return None
            size = [0.0, 0.0]
            for i in range(2):
                if newsize[i] > 0 or auto[i]:
                    lo, hi = flat_extent_exact(self, s, child, i)
                    size[i] = hi - lo
            # Polygon2d::resize
            maxdim = 1 if newsize[1] and newsize[1] > newsize[0] else 0
            sc = [newsize[i] / size[i] if newsize[i] > 0 else 1.0 for i in range(2)]
            autoscale = newsize[maxdim] / size[maxdim] if newsize[maxdim] > 0 else 1.0
            k = [sc[i] if not auto[i] or newsize[i] > 0 else autoscale for i in range(2)]
            return flat_moved(child, m @ np.diag([k[0], k[1], 1.0]))
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
            kids = [k for k in (self.flat(c, np.eye(3)) for c in live) if k is not None]
            if not kids:
                return None
            try:
                return minkowski_flat(kids, m)
            except ValueError as e:
                raise self.err(s, str(e))
        op = name if name in ("intersection", "difference", "hull") else "union"
        return self.flat_kids(s, op, m)

    def resize(self, s, a, xf, mat):
        """3-D resize: the children's exact box in the resize's frame, then
        CGAL_Nef_polyhedron::resize's scale about the origin."""
        newsize, auto = resize_args(self, s, a)
        n0 = len(self.scene.leaves)
        node = self.union([k for k in (self.node(c, np.eye(4), mat) for c in s.children) if k is not None])
        del self.scene.leaves[n0:]
        if node is None:
            return None
        lo, hi = exact_box(self, s, node)
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
                t = shadow_tree(moved_node(node, M))
            except ValueError as e:
                raise self.err(st, str(e))
            if t is None:
                return None
            lo, hi = flat_box(t)
            return t, ("framed", t, lo, hi)
        if f[0] == "section":
            _, node, m, st = f
            M = np.eye(4)
            M[np.ix_([0, 1, 3], [0, 1, 3])] = m
            moved = moved_node(node, M)
            lo, hi = box(moved)
            if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
                raise self.err(st, "the projection of an unbounded solid is not in the oracle")
            if lo[2] > 0 or hi[2] < 0 or np.any(lo > hi):
                return None
            size = hi - lo
            big = (lo[:2] - size[:2] - 1.0, hi[:2] + size[:2] + 1.0)
            try:
                t = section_tree(moved, big)
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
        if has_section(child):
            raise self.err(s, "an offset of a projection is not in the oracle")
        if d == 0:
            return flat_moved(child, m)
        try:
            pieces = offset_pieces(child, join, d)
        except ValueError as e:
            raise self.err(s, str(e))
        if pieces is None:
            return None
        if pieces[0] != "op":
            return flat_moved(pieces, m)
        if len(pieces) == 4:
            # One curved outline's pieces keep their own mark.
            return ("op", "union", [flat_moved(pieces, m)], (join, d, child, m))
        return ("op", pieces[1], [flat_moved(k, m) for k in pieces[2]], (join, d, child, m))

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
            return text_2d(self, s, a, place)
        if k == "import":
            f = import_2d(self, s, a)
            return None if f is None else flat_moved(f, m)
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
        if paths is None:
            if len(pts) < 3:
                return None
            paths = [list(range(len(pts)))]
        loops = []
        for path in paths:
            if not isinstance(path, list) or not all(map(number, path)):
                raise self.err(s, "paths of polygon must be lists of indices")
            idx = [int(i) for i in path if 0 <= int(i) < len(pts) and i >= 0]
            if len(idx) >= 3:
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
            f = import_2d(self, s, d)
        else:
            f = self.flat_kids(s, "union", np.eye(3))
        if has_section(f):
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
                check_twistable(self, s, f, twist, sc)
                return self.leaf(s, "linear_extrude", dict(flat=f, h=h, z0=z0, scale=None, scale2=sc, twist=twist), xf, mat)
            return self.leaf(s, "linear_extrude", dict(flat=f, h=h, z0=z0, scale=sc[0]), xf, mat)
        angle = num(self.path, s, a, "angle", 360.0)
        if angle <= -360 or angle > 360:
            angle = 360.0
        if f is None or angle == 0:
            return None
        lo, hi = flat_x_range(f)
        if lo < 0 < hi:
            # OpenSCAD's error: it renders the rest without this.
            return None
        return self.leaf(s, "rotate_extrude", dict(flat=f, angle=angle), xf, mat)

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
                sc.lights.append(("ambient", c, None))
            elif s.name == "directional_light":
                d = vec(self.path, s, a, "direction")
                sc.lights.append(("directional", c, d / np.linalg.norm(d)))
            else:
                sc.lights.append(("point", c, vec(self.path, s, a, "position")))


# --------------------------------------------------------------------------
# The seed's display list (.ray)
# --------------------------------------------------------------------------


def read_ray(path, text):
    """Slide 32's format: one statement a line; `surface` takes ten numbers
    over as many lines as it needs and applies to the spheres after it."""
    sc = Scene()
    eye, lookat, up, fov = np.array([0.0, 0, 10]), np.zeros(3), np.array([0.0, 1, 0]), 30.0
    sc.background = np.zeros(3)
    words = []  # (word, line, col)
    for ln, line in enumerate(text.split("\n"), 1):
        line = re.split(r"#|//", line, maxsplit=1)[0]
        for m in re.finditer(r"\S+", line):
            words.append((m.group(), ln, m.start() + 1))
    i, mat, spheres = 0, None, []

    def nums(k):
        nonlocal i
        out = []
        for _ in range(k):
            if i >= len(words):
                raise ReadError(path, words[-1][1], words[-1][2], "expected a number")
            w, ln, col = words[i]
            try:
                out.append(float(w))
            except ValueError:
                raise ReadError(path, ln, col, f"expected a number, found {w!r}")
            i += 1
        return np.array(out)

    while i < len(words):
        w, ln, col = words[i]
        i += 1
        if w == "eye":
            eye = nums(3)
        elif w == "lookat":
            lookat = nums(3)
        elif w == "up":
            up = nums(3)
        elif w == "fov":
            fov = float(nums(1)[0])
        elif w == "background":
            sc.background = nums(3)
        elif w == "light":
            c = nums(3)
            kind = words[i][0]
            i += 1
            if kind == "ambient":
                sc.lights.append(("ambient", c, None))
            elif kind == "directional":
                d = nums(3)
                sc.lights.append(("directional", c, d / np.linalg.norm(d)))
            elif kind == "point":
                sc.lights.append(("point", c, nums(3)))
            else:
                raise ReadError(path, ln, col, f"unknown light kind {kind!r}")
        elif w == "surface":
            n = nums(10)
            mat = dict(color=n[:3], ka=n[3], kd=n[4], ks=n[5], ns=n[6], kr=n[7], kt=n[8], ior=n[9])
        elif w == "sphere":
            n = nums(4)
            st = Stmt("sphere", [], [], "", ln, col)
            leaf = Leaf("sphere", dict(r=float(n[3])), affine(t=n[:3]), dict(mat or CORNFIELD), st)
            leaf.id = len(sc.leaves)
            sc.leaves.append(leaf)
            spheres.append(leaf)
        else:
            raise ReadError(path, ln, col, f"unknown statement {w!r}")
    sc.camera = (eye, lookat, up, fov)
    sc.root = Reader.union(spheres)
    if not sc.lights:
        sc.lights = default_lights()
    return sc


# --------------------------------------------------------------------------
# Bounds and the default camera
# --------------------------------------------------------------------------

EVERYTHING = (np.full(3, -np.inf), np.full(3, np.inf))
EMPTY = (np.full(3, np.inf), np.full(3, -np.inf))
UNIT = (-np.ones(3), np.ones(3))


def leaf_box(leaf):
    """The exact world box of a leaf."""
    if leaf.kind == "hull":
        return combine_boxes("union", [leaf_box(x) for x in leaf.params["parts"]])
    if leaf.kind == "minkowski":
        # Supports add: so do boxes.
        bs = [combine_boxes("union", [leaf_box(x) for x in o]) for o in leaf.params["operands"]]
        return sum(b[0] for b in bs), sum(b[1] for b in bs)
    if leaf.kind in EXTRUSIONS:
        return extrusion_box(leaf)
    m, p = leaf.matrix, leaf.params
    if leaf.kind == "polyhedron":
        # The box of the placed vertices (of the faces; a point no face
        # uses is not part of the solid).
        used = sorted({i for f in p["faces"] for i in f})
        w = p["points"][used] @ m[:3, :3].T + m[:3, 3]
        return w.min(axis=0), w.max(axis=0)
    L, t = m[:3, :3], m[:3, 3]
    row = lambda cols: np.sqrt(sum(L[:, c] ** 2 for c in cols))
    if leaf.kind == "sphere":
        e = p["r"] * row([0, 1, 2])
        return t - e, t + e
    if leaf.kind == "torus":
        e = p["R"] * row([0, 1]) + p["r"] * row([0, 1, 2])
        return t - e, t + e
    if leaf.kind == "cylinder":
        z0 = -p["h"] / 2 if p["center"] else 0.0
        e = row([0, 1])
        c0, c1 = L @ [0, 0, z0] + t, L @ [0, 0, z0 + p["h"]] + t
        return np.minimum(c0 - e * p["r1"], c1 - e * p["r2"]), np.maximum(c0 + e * p["r1"], c1 + e * p["r2"])
    if leaf.kind == "cube":
        s = p["size"]
        lo = -s / 2 if p["center"] else np.zeros(3)
        corners = [L @ (lo + s * np.array([(i >> k) & 1 for k in range(3)])) + t for i in range(8)]
        return np.min(corners, axis=0), np.max(corners, axis=0)
    # halfspace n.x <= offset: bounded on one side when axis-aligned
    n = np.linalg.inv(L).T @ p["normal"]
    lo, hi = EVERYTHING[0].copy(), EVERYTHING[1].copy()
    nz = [i for i in range(3) if n[i] != 0]
    if len(nz) == 1:
        q = L @ (p["normal"] * p["offset"] / (p["normal"] @ p["normal"])) + t
        i = nz[0]
        if n[i] > 0:
            hi[i] = q[i]
        else:
            lo[i] = q[i]
    return lo, hi


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
    size = num(rd.path, s, a, "size", 10.0)
    spacing = num(rd.path, s, a, "spacing", 1.0)
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


def flat_moved(f, m):
    """A 2-D tree moved by the plane matrix m (3x3, homogeneous)."""
    if f[0] in ("section", "shadow"):
        return (f[0], f[1], m @ f[2], f[3])
    if f[0] == "faces":
        return ("faces", [ccw(l @ m[:2, :2].T + m[:2, 2]) for l in f[1]])
    if f[0] == "poly":
        return ("poly", [l @ m[:2, :2].T + m[:2, 2] for l in f[1]])
    if f[0] == "ellipse":
        return ("ellipse", m[:2, :2] @ f[1], m[:2, :2] @ f[2] + m[:2, 2])
    if f[0] == "curves":
        # A control is one point (quadratic) or two (cubic, a 2 x 2 array).
        mv = lambda q: None if q is None else q @ m[:2, :2].T + m[:2, 2]
        return ("curves", [[(mv(q), mv(c)) for q, c in l] for l in f[1]])
    if len(f) == 4 and f[3][0] == "svg":
        moved = [(m @ g, [part_moved(x, m) for x in parts], sl) for g, parts, sl in f[3][1]]
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("svg", moved))
    if len(f) == 4 and f[3][0] == "drawing":
        _, paths, circles = f[3]
        mv = lambda q: m[:2, :2] @ q + m[:2, 2]
        arc = lambda x: None if x is None else (mv(x[0]), x[1] * math.sqrt(abs(np.linalg.det(m[:2, :2]))), mv(x[2]))
        moved = ([[(mv(p), arc(x)) for p, x in path] for path in paths], [(mv(c), r * math.sqrt(abs(np.linalg.det(m[:2, :2])))) for c, r in circles])
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("drawing",) + moved)
    if len(f) == 4 and f[3][0] == "bands":
        # Distances scale with a similarity's factor.
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("bands", f[3][1] * math.sqrt(abs(np.linalg.det(m[:2, :2])))))
    if len(f) == 4 and f[3][0] == "kites":
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], ("kites", f[3][1] * float(np.linalg.norm(m[:2, :2], 2))))
    if len(f) == 4:
        join, d, child, m0 = f[3]
        return ("op", f[1], [flat_moved(k, m) for k in f[2]], (join, d, child, m @ m0))
    return ("op", f[1], [flat_moved(k, m) for k in f[2]])


def outward_normals(loop, loops):
    """Each edge's unit outward normal (the even-odd region is not on its
    side just off the edge's middle)."""
    from_pts = np.asarray(loop)
    out = []
    size = max(float(np.abs(np.concatenate(loops)).max()), 1e-300)
    for i in range(len(from_pts)):
        a, b = from_pts[i], from_pts[(i + 1) % len(from_pts)]
        e = b - a
        n = np.array([e[1], -e[0]]) / np.linalg.norm(e)
        mid = (a + b) / 2 + n * 1e-9 * size
        out.append(-n if even_odd_inside(loops, mid) else n)
    return out


def even_odd_inside(loops, p):
    inside = False
    for l in loops:
        for a, b in zip(l, np.roll(l, -1, axis=0)):
            if (a[1] > p[1]) != (b[1] > p[1]):
                x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                inside ^= x > p[0]
    return inside


def straight_loops(f):
    """The loops of the boundary of a 2-D tree of straight polygons (union,
    intersection, difference), by manifold's boolean (Clipper2's, on its
    grid of 1e-8); None for a tree with other leaves."""

    def straight(g):
        return g[0] == "poly" or g[0] == "op" and len(g) == 3 and g[1] in ("union", "intersection", "difference") and all(map(straight, g[2]))

    if not straight(f):
        return None
    import manifold3d as mf

    def cs(g):
        if g[0] == "poly":
            return mf.CrossSection([l.tolist() for l in g[1]], mf.FillRule.EvenOdd)
        kids = [cs(k) for k in g[2]]
        if g[1] == "union":
            return mf.CrossSection.batch_boolean(kids, mf.OpType.Add)
        if g[1] == "intersection":
            return mf.CrossSection.batch_boolean(kids, mf.OpType.Intersect)
        return kids[0] - mf.CrossSection.batch_boolean(kids[1:], mf.OpType.Add)

    return [np.asarray(l, dtype=float) for l in cs(f).to_polygons()]


def offset_pieces(f, join, d):
    """OpenSCAD's offset of a 2-D tree as the CSG of plain 2-D leaves it
    is (Clipper's joins: round = the disc of radius |d| at a corner, miter =
    the kite to the two offset edges' meeting point, square = that kite cut
    across the corner's bisector at distance |d|): growing a simple polygon
    is it, the band each edge sweeps moving out by d, and a join at each
    convex corner; shrinking is it minus the bands swept inward and the
    joins at its reflex corners. A circle grows to radius R + d. Growing
    maps over a union, shrinking over an intersection; anything else is
    not in the oracle."""
    if f[0] == "op":
        # Shrinking a union of shapes whose boxes are apart: each by itself
        # (a disc inside a union of disjoint closed sets lies in one).
        apart = f[1] == "union" and d < 0 and boxes_apart(f[2])
        if f[1] == "union" and (d > 0 or apart) or f[1] == "intersection" and d < 0:
            parts = [offset_pieces(k, join, d) for k in f[2]]
            if f[1] == "intersection" and any(p is None for p in parts):
                return None
            parts = [p for p in parts if p is not None]
            return None if not parts else parts[0] if len(parts) == 1 else ("op", f[1], parts)
        loops = straight_loops(f)
        if loops is None:
            swept = swept_pieces(f, join, d)
            if swept is None:
                raise ValueError(f"offset of a 2-D {f[1]} by {d:g} is not in the oracle")
            return swept
        # Any other combination of straight polygons: its boundary's loops
        # (manifold's boolean), offset as one polygon.
        return offset_pieces(("poly", loops), join, d) if loops else None
    if f[0] == "ellipse":
        A = f[1]
        r = math.hypot(A[0, 0], A[1, 0])
        if abs(A[:, 0] @ A[:, 1]) > 1e-12 * r * r or abs(math.hypot(A[0, 1], A[1, 1]) - r) > 1e-12 * r:
            raise ValueError("offset of an ellipse is not in the oracle")
        return ("ellipse", np.eye(2) * (r + d), f[2]) if r + d > 0 else None
    if f[0] == "curves":
        return curved_offset_pieces(f, join, d)
    # A repeated point makes an edge of no length: left out (and a loop
    # left with fewer than 3 points, unless none is left).
    kept = [np.asarray([l[i] for i in range(len(l)) if np.any(l[i] != l[(i + 1) % len(l)])], float) for l in f[1]]
    kept = [l for l in kept if len(l) >= 3]
    loops = kept if kept else f[1]
    k, side = abs(d), (1.0 if d > 0 else -1.0)
    pieces = []
    for l in loops:
        ns = outward_normals(l, loops)
        m = len(l)
        for i in range(m):
            a, v, b = l[(i - 1) % m], l[i], l[(i + 1) % m]
            n1, n2 = ns[(i - 1) % m] * side, ns[i] * side
            pieces.append(("poly", [np.array([v, b, b + k * n2, v + k * n2])]))
            t1, t2 = v - a, b - v
            if (t2 @ n1) >= 0 or t1[0] * t2[1] - t1[1] * t2[0] == 0:
                continue  # no join where the offset side sees the corner reflex
            pieces.append(join_piece(join, v, n1, n2, t1, t2, k))
    body = ("poly", loops)
    return ("op", "union" if d > 0 else "difference", [body] + pieces)


def plain_op(g):
    """Whether g is a union, intersection or difference of 2-D trees (an
    offset's pieces are one too)."""
    return g[0] == "op" and g[1] in ("union", "intersection", "difference") and (len(g) == 3 or len(g) == 4 and g[3][0] in ("round", "miter", "square", "kites"))


def edges_and_circles(f, combines):
    """The polygon edges (a, b) and circles (c, r) of a 2-D tree whose
    combinations pass `combines`; None for another leaf."""
    segs, circles = [], []

    def leaves(g):
        if g[0] == "poly":
            segs.extend((np.asarray(l[i], float), np.asarray(l[(i + 1) % len(l)], float)) for l in g[1] for i in range(len(l)))
            return True
        if g[0] == "ellipse":
            if not is_circle(g[1]):
                return False
            circles.append((np.asarray(g[2], float), float(np.linalg.norm(g[1][:, 0]))))
            return True
        return combines(g) and all(leaves(k) for k in g[2])

    return (segs, circles) if leaves(f) else None


def boundary_strokes(f):
    """The boundary of a 2-D tree of straight polygons and circles as
    strokes with the region on their left — ("line", p, q) and ("arc", c,
    r, a0, span, convex): the circle's angles a0 to a0 + span, the region
    on the centre's side when convex — and the distance within which two
    points are one; None for other leaves. Each polygon edge is cut where
    any other edge or circle crosses it, each circle where anything
    crosses it, and a piece kept where the region is on exactly one of its
    sides, 1e-9 of the tree's size off the piece's middle."""
    got = edges_and_circles(f, plain_op)
    if got is None or not got[1]:
        return None
    segs, circles = got
    size = max([float(np.abs(q).max()) for sg in segs for q in sg] + [float(np.abs(c).max()) + r for c, r in circles])
    eps = 1e-9 * size
    inside = lambda q: bool(flat_inside(f, q))

    def seg_circle(a, b, c, r):
        d = b - a
        A, B, C = d @ d, 2 * (a - c) @ d, (a - c) @ (a - c) - r * r
        disc = B * B - 4 * A * C
        if A == 0 or disc < 0:
            return []
        return [u for u in ((-B - math.sqrt(disc)) / (2 * A), (-B + math.sqrt(disc)) / (2 * A)) if 0 <= u <= 1]

    out = []
    for i, (a, b) in enumerate(segs):
        d = b - a
        if not np.any(d):
            continue
        us = [0.0, 1.0]
        for j, (p0, q0) in enumerate(segs):
            e = q0 - p0
            den = d[0] * e[1] - d[1] * e[0]
            if j == i:
                continue
            if abs(den) <= 1e-12 * np.linalg.norm(d) * np.linalg.norm(e):
                # Along the same line: cut at the other edge's ends.
                off = lambda x: abs((x - a)[0] * d[1] - (x - a)[1] * d[0]) / np.linalg.norm(d)
                if off(p0) <= eps and off(q0) <= eps:
                    us += [float((p0 - a) @ d / (d @ d)), float((q0 - a) @ d / (d @ d))]
                continue
            w = p0 - a
            u, v = (w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den
            if 0 <= u <= 1 and 0 <= v <= 1:
                us.append(u)
        for c, r in circles:
            us += seg_circle(a, b, c, r)
        us = sorted(u for u in us if 0 <= u <= 1)
        nrm = np.array([-d[1], d[0]]) / np.linalg.norm(d)
        for u0, u1 in zip(us, us[1:]):
            if u1 > u0:
                mid = a + (u0 + u1) / 2 * d
                left, right = inside(mid + eps * nrm), inside(mid - eps * nrm)
                if left != right:
                    p0, p1 = a + u0 * d, a + u1 * d
                    out.append(("line", p0, p1) if left else ("line", p1, p0))
    for i, (c, r) in enumerate(circles):
        angs = []
        for a, b in segs:
            angs += [math.atan2(*(a + u * (b - a) - c)[::-1]) for u in seg_circle(a, b, c, r)]
        for j, (c2, r2) in enumerate(circles):
            dd = c2 - c
            l = float(np.linalg.norm(dd))
            if j != i and 0 < l <= r + r2 and l >= abs(r - r2):
                x = (r * r - r2 * r2 + l * l) / (2 * l)
                h = math.sqrt(max(r * r - x * x, 0.0))
                mid, perp = c + dd * x / l, np.array([-dd[1], dd[0]]) / l
                angs += [math.atan2(*(q - c)[::-1]) for q in (mid + h * perp, mid - h * perp)]
        angs = sorted(angs)
        spans = [(a0, a1 - a0) for a0, a1 in zip(angs, angs[1:] + [angs[0] + 2 * math.pi]) if a1 > a0] if angs else [(0.0, 2 * math.pi)]
        for a0, span in spans:
            u = np.array([math.cos(a0 + span / 2), math.sin(a0 + span / 2)])
            outer, inner = inside(c + (r + eps) * u), inside(c + (r - eps) * u)
            if outer != inner:
                out.append(("arc", c, r, a0, span, inner))
    return out, eps


def swept_pieces(f, join, d):
    """Any other offset of a 2-D tree of polygons and circles, from its
    boundary's strokes: R grown is R with every point within |d| of its
    boundary, R shrunk is R without them; the points within |d| of a line
    stroke are its two-sided band and a disc at each end, of an arc the
    annular sector over its angles (radii r -+ |d|) and the same discs.
    Miter and square joins add (take away) the kite at each corner the
    offset side sees as convex. None for other leaves."""
    got = boundary_strokes(f)
    if got is None:
        return None
    strokes, tol = got
    k, side = abs(d), (1.0 if d > 0 else -1.0)
    pieces, ends = [f], []

    def ends_of(st):
        if st[0] == "line":
            return st[1], st[2]
        _, c, r, a0, span, convex = st
        p0, p1 = (c + r * np.array([math.cos(a), math.sin(a)]) for a in (a0, a0 + span))
        return (p0, p1) if convex else (p1, p0)

    def tangent(st, at_end):
        if st[0] == "line":
            t = st[2] - st[1]
            return t / np.linalg.norm(t)
        _, c, r, a0, span, convex = st
        a = a0 + span if convex == at_end else a0
        t = np.array([-math.sin(a), math.cos(a)])
        return t if convex else -t

    for st in strokes:
        if st[0] == "line":
            p0, p1 = st[1], st[2]
            t = p1 - p0
            n = np.array([-t[1], t[0]]) * (k / np.linalg.norm(t))
            pieces.append(("poly", [np.array([p0 - n, p1 - n, p1 + n, p0 + n])]))
        else:
            _, c, r, a0, span, _ = st
            pieces += sector_pieces(c, r - k, r + k, a0, span)
            if span >= 2 * math.pi:
                continue
        for e in ends_of(st):
            if all(np.linalg.norm(x - e) > tol for x in ends):
                ends.append(e)
    pieces += [("ellipse", np.eye(2) * k, e.copy()) for e in ends]
    if join != "round":
        kites, reach = [], 0.0
        # Corners join the strokes that are not whole circles, not within
        # 1000 tol long (slivers where a band's edge meets a circle
        # tangent), and not copies of another: the next stroke starts
        # nearest the end, within 1000 tol; two within tol touch.
        slack, chain = 1e3 * tol, []
        for st in strokes:
            p0, p1 = ends_of(st)
            whole = st[0] == "arc" and st[4] >= 2 * math.pi
            copy = any(np.linalg.norm(ends_of(o)[0] - p0) <= tol and np.linalg.norm(ends_of(o)[1] - p1) <= tol for o in chain)
            if not whole and np.linalg.norm(p1 - p0) > slack and not copy:
                chain.append(st)
        for st in chain:
            v = ends_of(st)[1]
            nxt = sorted((float(np.linalg.norm(ends_of(o)[0] - v)), i) for i, o in enumerate(chain))
            nxt = [x for x in nxt if x[0] <= slack]
            # Those within tol along one direction overlap: any one serves.
            one_way = nxt and all(np.linalg.norm(tangent(chain[i], False) - tangent(chain[nxt[0][1]], False)) <= 1e-9 for l, i in nxt if l <= tol)
            if not nxt or len(nxt) > 1 and nxt[1][0] <= tol and not one_way:
                raise ValueError("a sharp offset of an outline that touches itself is not in the oracle")
            t1, t2 = tangent(st, True), tangent(chain[nxt[0][1]], False)
            n1, n2 = np.array([t1[1], -t1[0]]) * side, np.array([t2[1], -t2[0]]) * side
            if t2 @ n1 >= 0 or 1 - n1 @ n2 <= 1e-12:
                continue
            kites.append(join_piece(join, v, n1, n2, t1, t2, k))
            reach = max(reach, max(float(np.linalg.norm(q - v)) for q in kites[-1][1][0]))
        if kites:
            # Marked with their reach: a flattened circle's last chord
            # turns a kite's side about its corner (tools/oracle/oracle.py).
            pieces.append(("op", "union", kites, ("kites", reach)))
    return ("op", "union" if d > 0 else "difference", pieces)


def sector_pieces(c, r0, r1, a0, span):
    """The annular sector about c between radii r0 (none below 0) and r1
    over the angles a0 to a0 + span as 2-D trees: a ring for a whole turn,
    else sectors of at most a half turn, each the disc r1 met with its
    wedge cut to the sector's exact box (csgrt's framing), less disc r0."""
    disc = lambda r: ("ellipse", np.eye(2) * r, np.asarray(c, float).copy())
    hole = lambda g: ("op", "difference", [g, disc(r0)]) if r0 > 0 else g
    if span >= 2 * math.pi:
        return [hole(disc(r1))]
    m = max(1, math.ceil(span / math.pi))
    at = lambda a, r: c + r * np.array([math.cos(a), math.sin(a)])
    out = []
    for i in range(m):
        b0 = a0 + span * i / m
        b1 = b0 + span / m
        pts = [at(b0, r1), at(b1, r1)] + ([at(b0, r0), at(b1, r0)] if r0 > 0 else [np.asarray(c, float)])
        pts += [at(q * math.pi / 2, r1) for q in range(-4, 10) if b0 < q * math.pi / 2 < b1]
        lo, hi = np.min(pts, axis=0), np.max(pts, axis=0)
        wedge = [np.asarray(c, float), at(b0, 2 * r1), at((b0 + b1) / 2, 2 * r1), at(b1, 2 * r1)]
        # The wedge met with the box: cut by each of its four sides.
        for axis, bound, sign in ((0, lo[0], 1), (0, hi[0], -1), (1, lo[1], 1), (1, hi[1], -1)):
            cut = []
            for j, q0 in enumerate(wedge):
                q1 = wedge[(j + 1) % len(wedge)]
                s0, s1 = (q0[axis] - bound) * sign, (q1[axis] - bound) * sign
                if s0 >= 0:
                    cut.append(q0)
                if (s0 >= 0) != (s1 >= 0):
                    cut.append(q0 + (q1 - q0) * (s0 / (s0 - s1)))
            wedge = cut
        if len(wedge) >= 3:
            out.append(hole(("op", "intersection", [disc(r1), ("poly", [np.array(wedge)])])))
    return out


def outline_box(f):
    """A box (lo, hi) holding a 2-D tree (its leaves' points and control
    points; a combination's, all of its leaves'), or None for a projection."""
    if f[0] in ("poly", "faces"):
        pts = np.concatenate([np.asarray(l, float) for l in f[1]])
        return pts.min(axis=0), pts.max(axis=0)
    if f[0] == "curves":
        pts = np.array([q for l in f[1] for e in l for q in ([e[0]] + ([] if e[1] is None else list(np.asarray(e[1], float).reshape(-1, 2))))], float)
        return pts.min(axis=0), pts.max(axis=0)
    if f[0] == "ellipse":
        h = np.array([math.hypot(f[1][0, 0], f[1][0, 1]), math.hypot(f[1][1, 0], f[1][1, 1])])
        return f[2] - h, f[2] + h
    if f[0] != "op":
        return None
    bs = [outline_box(k) for k in f[2]]
    if any(b is None for b in bs):
        return None
    return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)


def boxes_apart(kids):
    """Whether no two of the 2-D trees' boxes meet."""
    bs = [outline_box(k) for k in kids]
    if any(b is None for b in bs):
        return False
    for i in range(len(bs)):
        for j in range(i + 1, len(bs)):
            (a0, a1), (b0, b1) = bs[i], bs[j]
            if np.all(b0 <= a1) and np.all(a0 <= b1):
                return False
    return True


def curved_offset_pieces(f, join, d):
    """A curved outline (a glyph's quadratic edges) offset by d: the points
    within |d| of it (grown) or of the inside farther than |d| from it
    (shrunk), whose boundary lies at |d| from the edges — on the curves
    their points trace along their normals and the circles about their
    ends. The oracle meshes manifold's own offset of the flattened outline
    (cross_section); these pieces carry the bounds and the faces: the
    outline, marked ("bands", |d|) (its edges' faces lie |d| from them),
    a disc at each corner, and with miter or square joins the kite (or cut
    kite) at each sharp corner that the offset side sees as convex."""
    k, side = abs(d), (1.0 if d > 0 else -1.0)
    if any(c is not None and np.asarray(c).ndim == 2 for _, c, _ in curve_pieces(f)):
        raise ValueError("offset of cubic curves is not in the oracle")
    fine = [np.concatenate([bezier_eval(bezier_points(l[i][0], l[i][1], l[(i + 1) % len(l)][0]), np.arange(64) / 64) for i in range(len(l))]) for l in f[1]]
    size = max(float(np.abs(np.concatenate(fine)).max()), 1e-300)

    def outward(P, u, t):
        # The unit normal at B(u) on the side the region is not on.
        n = np.array([t[1], -t[0]]) / np.linalg.norm(t)
        return -n if even_odd_inside(fine, bezier_eval(P, 0.5) + n * 1e-9 * size) else n

    pieces = [f]
    for l in f[1]:
        m = len(l)
        for i in range(m):
            pa, ca = l[(i - 1) % m]
            v, cv = l[i]
            nxt = l[(i + 1) % m][0]
            pieces.append(("ellipse", np.eye(2) * k, np.array(v, float)))
            if join == "round":
                continue
            P1, P2 = bezier_points(pa, ca, v), bezier_points(v, cv, nxt)
            t1 = v - (P1[-2] if not np.array_equal(P1[-2], v) else P1[0])
            t2 = (P2[1] if not np.array_equal(P2[1], v) else P2[-1]) - v
            if np.linalg.norm(t1) == 0 or np.linalg.norm(t2) == 0:
                continue
            # The sides at the middles, carried to the ends (a quadratic
            # turns less than half a turn: its normal keeps its side).
            mid1 = bezier_eval(P1, 0.5) - bezier_eval(P1, 0.5 - 1e-6)
            mid2 = bezier_eval(P2, 0.5 + 1e-6) - bezier_eval(P2, 0.5)
            s1 = np.sign(outward(P1, 0.5, mid1) @ np.array([mid1[1], -mid1[0]]))
            s2 = np.sign(outward(P2, 0.5, mid2) @ np.array([mid2[1], -mid2[0]]))
            n1 = s1 * np.array([t1[1], -t1[0]]) / np.linalg.norm(t1) * side
            n2 = s2 * np.array([t2[1], -t2[0]]) / np.linalg.norm(t2) * side
            if t2 @ n1 >= 0 or 1 - n1 @ n2 <= 1e-12:
                continue  # reflex as the offset side sees it, or tangent
            pieces.append(join_piece(join, v, n1, n2, t1, t2, k))
    return ("op", "union" if d > 0 else "difference", pieces, ("bands", k))


def join_piece(join, v, n1, n2, t1, t2, k):
    """Clipper's join at corner v (edges arriving along t1 and leaving
    along t2, offset-side unit normals n1 and n2) at distance k: the disc
    (round), the kite to the offset edges' meeting point (miter), or that
    kite cut across the bisector at distance k (square, and a miter beyond
    the limit)."""
    cos = float(n1 @ n2)
    if join == "round":
        return ("ellipse", np.eye(2) * k, v.copy())
    if join == "miter" and 1 + cos >= 2e-12:
        return ("poly", [np.array([v, v + k * n1, v + (n1 + n2) * (k / (1 + cos)), v + k * n2])])
    # The cut at distance k along the bisector meets the offset edges
    # k tan(theta / 4) beyond their ends.
    theta = math.atan2(abs(n1[0] * n2[1] - n1[1] * n2[0]), cos)
    run = k * math.tan(theta / 4)
    u1, u2 = t1 / np.linalg.norm(t1), t2 / np.linalg.norm(t2)
    return ("poly", [np.array([v, v + k * n1, v + k * n1 + run * u1, v + k * n2 - run * u2, v + k * n2])])


def convex_hull_2d(pts):
    """Andrew's monotone chain: the hull's corners, counter-clockwise."""
    pts = sorted(set(map(tuple, np.asarray(pts, dtype=float).tolist())))
    if len(pts) < 3:
        return np.array(pts)
    cross = lambda o, a, b: (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def convex_poly(f):
    """The corners of a 2-D leaf that is one convex polygon, else None."""
    if f[0] != "poly" or len(f[1]) != 1:
        return None
    loop = np.asarray(f[1][0], dtype=float)
    h = convex_hull_2d(loop)
    area = lambda l: 0.5 * abs(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1]))
    if len(h) < 3 or abs(area(h) - area(loop)) > 1e-12 * area(h):
        return None
    return h


def convex_parts(f):
    """[(corners, radius)] of a union of convex polygons and circles (a
    circle its centre and radius), else None: csgrt's convex pieces."""
    if f[0] == "ellipse":
        A = f[1]
        r = float(np.linalg.norm(A[:, 0]))
        if abs(A[:, 0] @ A[:, 1]) <= 1e-12 * r * r and abs(np.linalg.norm(A[:, 1]) - r) <= 1e-12 * r:
            return [(np.asarray(f[2], dtype=float)[None, :], r)]
        return None
    if f[0] == "poly":
        h = convex_poly(f)
        return None if h is None else [(h, 0.0)]
    if f[0] == "op" and f[1] == "union" and len(f) == 3:
        parts = [convex_parts(k) for k in f[2]]
        return None if any(p is None for p in parts) else [x for p in parts for x in p]
    return None


def grown_convex(pts, r, m):
    """The convex polygon of corners pts (counter-clockwise) grown by a
    disc of radius r, as csgrt writes it: each edge pushed out by r as one
    polygon, a disc on each corner; manifold's own offset of the polygon
    in the oracle's mesh."""
    n = len(pts)
    parts = [("ellipse", np.eye(2) * r, p.copy()) for p in pts] if r > 0 else []
    if n >= 3 and r > 0:
        out = []
        for i in range(n):
            a, b = pts[i], pts[(i + 1) % n]
            e = (b - a) / np.linalg.norm(b - a)
            o = np.array([e[1], -e[0]]) * r
            out += [a + o, b + o]
        parts.append(("poly", [np.array(out)]))
    elif n == 2 and r > 0:
        e = (pts[1] - pts[0]) / np.linalg.norm(pts[1] - pts[0])
        o = np.array([e[1], -e[0]]) * r
        parts.append(("poly", [np.array([pts[0] + o, pts[1] + o, pts[1] - o, pts[0] - o])]))
    elif n >= 3:
        parts.append(("poly", [pts.copy()]))
    if not parts:
        return None
    if len(parts) == 1:
        return flat_moved(parts[0], m)
    moved = [flat_moved(k, m) for k in parts]
    if n >= 3:
        return ("op", "union", moved, ("round", r, ("poly", [pts.copy()]), m))
    return ("op", "union", moved)


def translation_2d(v):
    return np.array([[1.0, 0.0, v[0]], [0.0, 1.0, v[1]], [0.0, 0.0, 1.0]])


def sum_choices(start, pieces):
    """Every choice of one (corners, radius) from each of pieces, summed onto
    start: the hull of the corners' sums, with the radii's sum."""
    combos = [start]
    for op in pieces:
        combos = [(convex_hull_2d((a[:, None, :] + b[None, :, :]).reshape(-1, 2)), ra + rb) for a, ra in combos for b, rb in op]
    return combos


def minkowski_flat(kids, m):
    """2-D minkowski() of flat trees read in its own frame, moved by m, as
    csgrt sums them: the circles' sum (centre c, radius r) grows the rest;
    unions of convex polygons and circles sum piece by piece (the hull of
    the corners' sums, grown by the radii's); one other shape grows by r as
    offset(r) does (the same pieces; manifold's own offset in the oracle's
    mesh). Any other sum is not in the oracle."""
    circles, rest = [], []
    for k in kids:
        c = convex_parts(k) if k[0] == "ellipse" else None
        (circles if c else rest).append(c[0] if c else k)
    c = sum((x[0][0] for x in circles), np.zeros(2))
    r = sum(x[1] for x in circles)
    pieces = [convex_parts(k) for k in rest]
    whole = [k for k, p in zip(rest, pieces) if p is None]
    pieces = [p for p in pieces if p is not None]
    if len(whole) == 1 and not pieces:
        child = flat_moved(whole[0], translation_2d(c))
        if r == 0:
            return flat_moved(child, m)
        if has_section(child):
            raise ValueError("a minkowski sum with a projection is not in the oracle")
        grown = offset_pieces(child, "round", r)
        if grown is None or grown[0] != "op":
            return None if grown is None else flat_moved(grown, m)
        return ("op", grown[1], [flat_moved(k, m) for k in grown[2]], ("round", r, child, m))
    if len(whole) == 1 and r == 0 and whole[0][0] == "poly" and all(rr == 0 for op in pieces for _, rr in op):
        # A + B = (A + b) u (edges of A + B) for a convex B (b a point of B):
        # A moved by B's first corner, and each edge's hull with B; in the
        # oracle's mesh, manifold's union of A's triangles' hulls with B.
        parts = []
        for b, _ in sum_choices((np.zeros((1, 2)), 0.0), pieces):
            shifted = flat_moved(whole[0], translation_2d(b[0]))
            kids = [flat_moved(shifted, m)]
            for l in whole[0][1]:
                for i in range(len(l)):
                    h = convex_hull_2d(np.concatenate([b + l[i], b + l[(i + 1) % len(l)]]))
                    if len(h) >= 3:
                        kids.append(flat_moved(("poly", [h]), m))
            parts.append(("op", "union", kids, ("sum", b, whole[0], m)))
        return parts[0] if len(parts) == 1 else ("op", "union", parts)
    if whole:
        raise ValueError("minkowski of 2-D shapes that are not convex, other than one with circles or one polygon with convex polygons, is not in the oracle")
    if not pieces:
        return flat_moved(("ellipse", np.eye(2) * r, c), m) if r > 0 else None
    parts = [g for g in (grown_convex(p, rr, m) for p, rr in sum_choices((c[None, :], r), pieces)) if g is not None]
    if not parts:
        return None
    return parts[0] if len(parts) == 1 else ("op", "union", parts)


def has_section(f):
    return f is not None and (f[0] in ("section", "shadow") or f[0] == "op" and any(has_section(k) for k in f[2]))


def flat_stmt(s):
    """Whether a statement makes a 2-D shape (its first live child decides
    for transforms, operations, colours and resize)."""
    if s.name in SHAPES_2D and s.name != "import" or s.name in ("offset", "projection"):
        return True
    if s.name == "import":
        f = next((v for k, v in s.args if k in ("file", None) and isinstance(v, str)), "")
        return f.lower().endswith((".dxf", ".svg"))
    if s.name in TRANSFORMS or s.name in ("union", "intersection", "difference", "group", "render", "color", "material", "resize", "hull", "minkowski"):
        live = [c for c in s.children if not ("%" in c.mods or "*" in c.mods)]
        return bool(live) and flat_stmt(live[0])
    return False


def resize_args(rd, s, a):
    ns = a.get("newsize", [])
    ns = [float(x) for x in ns] if isinstance(ns, list) else []
    ns = (ns + [0.0, 0.0, 0.0])[:3]
    au = a.get("auto", False)
    au = [bool(x) for x in au] if isinstance(au, list) else [bool(au)] * 3
    return ns, (au + [False, False, False])[:3]


def flat_extent_exact(rd, s, f, i):
    """The exact extent of a 2-D tree along axis i: leaves exactly, a union
    the join, a difference its first operand's when no subtracted box
    reaches its sides; anything else is not in the oracle."""
    if f[0] == "poly":
        v = np.concatenate([l[:, i] for l in f[1]])
        return v.min(), v.max()
    if f[0] == "curves":
        lo, hi = curve_extent(f)
        return lo[i], hi[i]
    if f[0] == "ellipse":
        h = float(np.linalg.norm(f[1][i]))
        return f[2][i] - h, f[2][i] + h
    if f[0] == "section":
        raise rd.err(s, "a resized projection is not in the oracle")
    rs = [flat_extent_exact(rd, s, k, i) for k in f[2]]
    if f[1] in ("union", "hull"):
        return min(r[0] for r in rs), max(r[1] for r in rs)
    if f[1] == "difference" and all(r[0] > rs[0][0] and r[1] < rs[0][1] for r in rs[1:]):
        return rs[0]
    if f[1] == "xor":
        # Even-odd: a far side only one operand reaches is in the result.
        lo, hi = min(r[0] for r in rs), max(r[1] for r in rs)
        if sum(r[0] == lo for r in rs) == 1 and sum(r[1] == hi for r in rs) == 1:
            return lo, hi
    raise rd.err(s, f"the extent of this 2-D {f[1]} is not in the oracle")


def exact_box(rd, s, node):
    """The exact box of a 3-D tree: each primitive's closed form (an
    extrusion's only under an axis-aligned matrix, where csgrt's framing
    box is exact), a union's join, a difference's first operand's when no
    subtracted box reaches its sides; anything else is not in the oracle."""
    if isinstance(node, Leaf):
        if node.kind in EXTRUSIONS:
            L = node.matrix[:3, :3]
            if node.kind != "linear_extrude" or twisted(node.params) or np.count_nonzero(L - np.diag(np.diag(L))):
                raise rd.err(s, "the exact extent of this extrusion is not in the oracle")
        if node.kind == "halfspace":
            raise rd.err(s, "the extent of a halfspace is not in the oracle")
        return leaf_box(node)
    bs = [exact_box(rd, s, c) for c in node.children]
    if node.op == "union":
        return combine_boxes("union", bs)
    if node.op == "difference" and all(np.all(b[0] > bs[0][0]) and np.all(b[1] < bs[0][1]) for b in bs[1:]):
        return bs[0]
    raise rd.err(s, f"the extent of this {node.op} is not in the oracle")


def has_slice(leaf):
    """Whether an extrusion leaf holds a projection's slice."""
    rec = lambda f: f[0] == "framed" or f[0] == "op" and any(rec(k) for k in f[2])
    return "frame" in leaf.params and rec(leaf.params["frame"])


def moved_node(node, M):
    """A 3-D tree with every leaf placed by M first."""
    if isinstance(node, Leaf):
        x = Leaf(node.kind, node.params, M @ node.matrix, node.material, node.stmt)
        return x
    return Op(node.op, [moved_node(c, M) for c in node.children])


def clip_poly(poly, g, c):
    """The convex polygon poly (k x 2) cut to g . p <= c (Sutherland-Hodgman)."""
    out = []
    k = len(poly)
    for i in range(k):
        a, b = poly[i], poly[(i + 1) % k]
        fa, fb = g @ a - c, g @ b - c
        if fa <= 0:
            out.append(a)
        if (fa < 0 < fb) or (fb < 0 < fa):
            out.append(a + (b - a) * (fa / (fa - fb)))
    return np.array(out) if len(out) >= 3 else None


def half_planes(poly, rows):
    """poly cut by each (g, c): g . p <= c; None when nothing is left. A
    row with g = 0 keeps all or nothing."""
    for g, c in rows:
        if not np.any(g):
            if 0.0 > c:
                return None
            continue
        poly = clip_poly(poly, g, c)
        if poly is None:
            return None
    return poly


def slab_rows(P, w, i, lo, hi):
    """The half-planes lo <= (P p + w)_i <= hi, a row exactly zero when P's
    row is negligible (a face parallel to the plane)."""
    g = P[i].copy()
    if np.linalg.norm(g) <= 1e-13 * np.linalg.norm(P):
        g[:] = 0.0
    return [(g, hi - w[i]), (-g, w[i] - lo)]


def conic_ellipse(Q, w, r):
    """The ellipse {p : |Q p + w| <= r} for Q of full column rank, as
    ("ellipse", A, c) (the image of the unit disc), or None when empty."""
    G = Q.T @ Q
    c = -np.linalg.solve(G, Q.T @ w)
    k = r * r - w @ w + c @ G @ c
    if k <= 0:
        return None
    A = math.sqrt(k) * np.linalg.cholesky(np.linalg.inv(G))
    return ("ellipse", A, c)


def mesh_slice(node):
    """The slice z = 0 of a placed mesh as ("poly", loops), filled even-odd:
    each face edge with ends on both sides meets the plane at one point
    (computed once an edge, so the two faces of an edge share it); a face
    crossing the plane gives the segment between its two such points, and
    the segments chain into loops. A point exactly in the plane is not in
    the oracle (which side it counts for is a convention)."""
    pts = node.params["points"] @ node.matrix[:3, :3].T + node.matrix[:3, 3]
    z = pts[:, 2]
    if np.any(z == 0):
        raise ValueError("a mesh point exactly in the slicing plane is not in the oracle")
    cut = {}

    def at(i, j):
        key = (min(i, j), max(i, j))
        if key not in cut:
            a, b = pts[key[0]], pts[key[1]]
            f = a[2] / (a[2] - b[2])
            cut[key] = len(cut), (a + f * (b - a))[:2]
        return cut[key][0]

    nxt = {}
    for f in node.params["faces"]:
        crossings = [at(f[k], f[(k + 1) % len(f)]) for k in range(len(f)) if (z[f[k]] > 0) != (z[f[(k + 1) % len(f)]] > 0)]
        for k in range(0, len(crossings) - 1, 2):
            a, b = crossings[k], crossings[k + 1]
            nxt.setdefault(a, []).append(b)
            nxt.setdefault(b, []).append(a)
    point = {i: p for i, p in cut.values()}
    loops, seen = [], set()
    for start in nxt:
        if start in seen:
            continue
        loop, prev, cur = [start], None, start
        seen.add(start)
        while True:
            step = [x for x in nxt[cur] if x != prev]
            if not step or step[0] == start:
                break
            prev, cur = cur, step[0]
            if cur in seen:
                break
            seen.add(cur)
            loop.append(cur)
        if len(loop) >= 3:
            loops.append(np.array([point[i] for i in loop]))
    return ("poly", loops) if loops else None


def ccw(loop):
    """A loop turned counter-clockwise."""
    x, y = loop[:, 0], loop[:, 1]
    area = float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return loop if area >= 0 else loop[::-1]


def shadow_tree(node):
    """The shadow on z = 0 of a 3-D union of meshes, boxes and spheres,
    exactly, as a 2-D tree: a mesh's or box's as the union of its faces'
    shadows, ("faces", loops counter-clockwise) filled where any loop is;
    a sphere's, the ellipse E u + c with E E^T = P P^T (P its matrix's x
    and y rows). The shadow of an intersection or a difference is not its
    operands', and not in the oracle; nor a cylinder's."""
    if isinstance(node, Op):
        if node.op != "union":
            raise ValueError(f"the shadow of a 3-D {node.op} is not in the oracle")
        kids = [k for k in (shadow_tree(c) for c in node.children) if k is not None]
        return None if not kids else kids[0] if len(kids) == 1 else ("op", "union", kids)
    m, p = node.matrix, node.params
    if node.kind == "polyhedron":
        pts = p["points"] @ m[:3, :3].T + m[:3, 3]
        loops = [ccw(pts[f][:, :2]) for f in p["faces"]]
        return ("faces", [l for l in loops if abs(float(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1]))) > 0])
    if node.kind == "cube":
        s0 = -p["size"] / 2 if p["center"] else np.zeros(3)
        c = [np.array([s0[0] + (i & 1) * p["size"][0], s0[1] + (i >> 1 & 1) * p["size"][1], s0[2] + (i >> 2 & 1) * p["size"][2]]) for i in range(8)]
        pts = np.array(c) @ m[:3, :3].T + m[:3, 3]
        faces = [[0, 1, 3, 2], [4, 5, 7, 6], [0, 1, 5, 4], [2, 3, 7, 6], [0, 2, 6, 4], [1, 3, 7, 5]]
        loops = [ccw(pts[f][:, :2]) for f in faces]
        return ("faces", [l for l in loops if abs(float(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1]))) > 0])
    if node.kind == "sphere":
        P = m[:2, :3] * p["r"]
        E = np.linalg.cholesky(P @ P.T)
        return ("ellipse", E, m[:2, 3].copy())
    raise ValueError(f"the shadow of a {node.kind} is not in the oracle")


def flat_box(f):
    """The box (lo, hi) of a shadow tree's leaves (csgrt's framing of it)."""
    if f[0] == "faces":
        pts = np.concatenate(f[1])
        return pts.min(axis=0), pts.max(axis=0)
    if f[0] == "ellipse":
        h = np.sqrt(f[1][:, 0] ** 2 + f[1][:, 1] ** 2)
        return f[2] - h, f[2] + h
    bs = [flat_box(k) for k in f[2]]
    return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)


def section_tree(node, big):
    """The slice z = 0 of a 3-D tree of spheres, boxes, cylinders and
    halfspaces, exactly, as a 2-D tree: a point p of the plane is in a
    leaf when its object point u = P p + w is (P, w from the leaf's inverse
    matrix). A sphere gives the ellipse |u| <= r; a box the polygon of its
    six half-planes; a cylinder the ellipse |u_xy| <= r (or, with its axis
    in the plane, a strip) met with its caps' half-planes; a halfspace a
    half-plane. Polygons are cut from the square `big`."""
    if isinstance(node, Op):
        kids = [section_tree(c, big) for c in node.children]
        if node.op == "intersection" and any(k is None for k in kids):
            return None
        if node.op == "difference" and kids[0] is None:
            return None
        live = [k for k in kids if k is not None]
        if not live:
            return None
        return live[0] if len(live) == 1 else ("op", node.op, live)
    lo, hi = big
    square = np.array([lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]], dtype=float)
    inv = np.linalg.inv(node.matrix)
    P, w = inv[:3, :2], inv[:3, 3]
    p = node.params
    poly = lambda rows: (lambda q: None if q is None else ("poly", [q]))(half_planes(square, rows))
    if node.kind == "sphere":
        return conic_ellipse(P, w, p["r"])
    if node.kind == "cube":
        s0 = -p["size"] / 2 if p["center"] else np.zeros(3)
        return poly([r for i in range(3) for r in slab_rows(P, w, i, s0[i], s0[i] + p["size"][i])])
    if node.kind == "cylinder" and p["r1"] == p["r2"]:
        z0 = -p["h"] / 2 if p["center"] else 0.0
        caps = slab_rows(P, w, 2, z0, z0 + p["h"])
        Q, r = P[:2], p["r1"]
        U, S, Vt = np.linalg.svd(Q)
        if S[1] <= 1e-13 * S[0]:
            # The axis in the plane: |w + e s| <= r with s = g . p, a strip.
            e, g = U[:, 0], S[0] * Vt[0]
            b, cc = e @ w[:2], w[:2] @ w[:2] - r * r
            disc = b * b - cc
            if disc <= 0:
                return None
            s0, s1 = -b - math.sqrt(disc), -b + math.sqrt(disc)
            return poly(caps + [(g, s1), (-g, -s0)])
        ell = conic_ellipse(Q, w[:2], r)
        if ell is None:
            return None
        if not np.any(caps[0][0]):
            return ell if caps[0][1] >= 0 and caps[1][1] >= 0 else None
        box_ = poly(caps)
        return None if box_ is None else ("op", "intersection", [ell, box_])
    if node.kind == "halfspace":
        n = p["normal"]
        return poly([(n @ P, p["offset"] - n @ w)])
    if node.kind == "polyhedron":
        return mesh_slice(node)
    raise ValueError(f"the slice of a {node.kind} is not in the oracle")


def check_twistable(rd, s, f, twist, sc):
    """The oracle twists and scales polygons, circles, ellipses and DXF
    drawings, not text or SVG drawings."""
    if f[0] == "curves":
        raise rd.err(s, "twisted text is not in the oracle")
    if len(f) == 4 and f[3][0] == "svg":
        raise rd.err(s, "a twisted SVG drawing is not in the oracle")
    if f[0] == "op":
        for k in f[2]:
            check_twistable(rd, s, k, twist, sc)


def twisted(p):
    """Whether an extrusion's parameters twist or scale unevenly."""
    return p.get("scale") is None


def twist_frame(p, t):
    """R(twist t) S(t)^-1 (OpenSCAD's section at fraction t, inverted): a
    world plane point times it is the region's point."""
    sx, sy = p["scale2"]
    sg = np.array([1 + (sx - 1) * t, 1 + (sy - 1) * t])
    a = math.radians(p["twist"]) * t
    c, s_ = math.cos(a), math.sin(a)
    return np.array([[c, -s_], [s_, c]]) @ np.diag(1 / sg)


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
        dpi = num(rd.path, s, a, "dpi", 72.0)
        return svg_tree(*svg_read(path, dpi if dpi >= 0.001 else 72.0, bool(a.get("center", False))))
    if not file.lower().endswith(".dxf"):
        raise rd.err(s, f"import of {file} is not in the oracle")
    origin = np.array(a.get("origin", [0.0, 0.0])[:2], float)
    pieces, circles = dxf_pieces(path, a.get("layer", a.get("layername", "")) or "", origin, num(rd.path, s, a, "scale", 1.0))
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
            out = chord is None or not even_odd_inside([chord], mid)
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
            ins = chord is not None and even_odd_inside([chord], x)
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


def svg_read(path, dpi, center):
    """(shapes, place): each shape (its transform, its parts) in user
    space, and the map from user space to OpenSCAD's plane."""
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    local = lambda el: el.tag.split("}")[-1]
    if local(root) != "svg":
        raise ValueError("the root element is not svg")
    vb = None
    if root.get("viewBox") is not None:
        vb = [float(x) for x in re.split(r"[\s,]+", root.get("viewBox").strip())]
        if len(vb) != 4 or vb[2] <= 0 or vb[3] <= 0:
            raise ValueError("a viewBox of no size")
    width = svg_mm(svg_length(root.get("width")), vb[2] if vb else None, dpi)
    height = svg_mm(svg_length(root.get("height")), vb[3] if vb else None, dpi)
    scale, align, origin = np.ones(2), np.zeros(2), np.zeros(2)
    if vb:
        origin = np.array(vb[:2])
        scale = np.array([width / vb[2], height / vb[3]])
        words = (root.get("preserveAspectRatio") or "xMidYMid meet").split()
        if words and words[0] == "defer":
            words = words[1:]
        al = words[0] if words else "xMidYMid"
        if al != "none":
            k = scale.max() if len(words) > 1 and words[1] == "slice" else scale.min()
            scale = np.array([k, k])
            pos = lambda code, page, v: {"Mid": page / 2 - k * v / 2, "Max": page - k * v}.get(code, 0.0)
            align = np.array([pos(al[1:4], width, vb[2]), pos(al[5:8], height, vb[3])])
    shapes = []

    def walk(el, m):
        for ch in el:
            name = local(ch)
            if name == "defs" or not isinstance(ch.tag, str):
                continue
            own = svg_transform(ch.get("transform"))
            if name in ("g", "text", "tspan"):
                walk(ch, m @ own)
            elif name in ("path", "rect", "circle", "ellipse", "line", "polyline", "polygon"):
                shapes.append((m @ own, svg_parts(ch, name)))
            elif name == "svg":
                raise ValueError("an svg inside the drawing is not in the oracle")
            else:
                walk(ch, m)

    walk(root, np.eye(3))
    if center:
        pts = []
        for m, parts in shapes:
            for x in parts:
                pts += [m[:2, :2] @ q + m[:2, 2] for q in svg_openscad_points(x)]
        pts = np.array(pts) * scale if pts else np.zeros((1, 2))
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
            P = bezier_points(a, sg[1] if sg[0] == "Q" else np.array(sg[1:3]), b)
            out += list(bezier_eval(P, np.arange(1, 21) / 20))
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
        kids.append(flat_moved(tree[0] if len(tree) == 1 else ("op", "xor", tree), mm))
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


def curve_pieces(f):
    """The edges of a ("curves", loops) leaf as (a, c or None, b)."""
    return [(l[i][0], l[i][1], l[(i + 1) % len(l)][0]) for l in f[1] for i in range(len(l))]


def bezier_points(a, c, b):
    """The control polygon of an edge: [a, b], [a, c, b] or [a, c1, c2, b]."""
    if c is None:
        return np.array([a, b])
    c = np.asarray(c, float)
    return np.array([a, c, b]) if c.ndim == 1 else np.array([a, c[0], c[1], b])


def bezier_eval(P, u):
    """Points of the Bézier curve with control points P at parameters u."""
    u = np.asarray(u, float)[..., None]
    k = len(P) - 1
    return sum(math.comb(k, i) * (1 - u) ** (k - i) * u**i * P[i] for i in range(k + 1))


def bezier_turning(P, i):
    """The parameters in (0, 1) where coordinate i of the curve is
    stationary (its derivative's roots)."""
    k = len(P) - 1
    if k < 2:
        return []
    d = [k * (P[j + 1][i] - P[j][i]) for j in range(k)]
    # The derivative in the power basis: a Bézier of degree k - 1.
    if k == 2:
        den = d[0] - d[1]
        return [d[0] / den] if den != 0 and 0 < d[0] / den < 1 else []
    qa, qb, qc = d[0] - 2 * d[1] + d[2], 2 * (d[1] - d[0]), d[0]
    if qa == 0:
        return [-qc / qb] if qb != 0 and 0 < -qc / qb < 1 else []
    disc = qb * qb - 4 * qa * qc
    if disc < 0:
        return []
    r = math.sqrt(disc)
    return [u for u in ((-qb - r) / (2 * qa), (-qb + r) / (2 * qa)) if 0 < u < 1]


def curve_extent(f):
    """The exact box (lo, hi) of a curves leaf: a curve's extremes are at
    its ends or where a coordinate's derivative vanishes."""
    pts = []
    for a, c, b in curve_pieces(f):
        pts.append(a)
        if c is not None:
            P = bezier_points(a, c, b)
            for i in range(2):
                pts += [bezier_eval(P, u) for u in bezier_turning(P, i)]
    pts = np.array(pts)
    return pts.min(axis=0), pts.max(axis=0)


def clip_right(loops):
    """Each loop cut to x >= 0 (Sutherland-Hodgman)."""
    out = []
    for l in loops:
        pts = []
        for i in range(len(l)):
            a, b = l[i], l[(i + 1) % len(l)]
            if a[0] >= 0:
                pts.append(a)
            if (a[0] >= 0) != (b[0] >= 0):
                f = a[0] / (a[0] - b[0])
                pts.append(np.array([0.0, a[1] + f * (b[1] - a[1])]))
        if len(pts) >= 3:
            out.append(np.array(pts))
    return out


def flat_mirror(f):
    """The tree mirrored in x = 0."""
    if f[0] == "curves":
        fl = lambda q: None if q is None else q * [-1.0, 1.0]
        return ("curves", [[(fl(q), fl(c)) for q, c in l] for l in f[1]])
    if f[0] == "poly":
        return ("poly", [l * [-1.0, 1.0] for l in f[1]])
    if f[0] == "ellipse":
        return ("ellipse", np.diag([-1.0, 1.0]) @ f[1], f[2] * [-1.0, 1.0])
    return ("op", f[1], [flat_mirror(k) for k in f[2]])


def flat_x_range(f):
    """The x extent of a 2-D tree (union joins, intersection meets, a
    difference keeps its first operand's), as csgrt reads OpenSCAD's axis
    rule for rotate_extrude."""
    if f[0] == "poly":
        xs = np.concatenate([l[:, 0] for l in f[1]])
        return xs.min(), xs.max()
    if f[0] == "curves":
        lo, hi = curve_extent(f)
        return lo[0], hi[0]
    if f[0] == "ellipse":
        h = math.hypot(f[1][0, 0], f[1][0, 1])
        return f[2][0] - h, f[2][0] + h
    rs = [flat_x_range(k) for k in f[2]]
    if f[1] in ("union", "xor", "hull"):
        return min(r[0] for r in rs), max(r[1] for r in rs)
    if f[1] == "intersection":
        return max(r[0] for r in rs), min(r[1] for r in rs)
    return rs[0]


def combine_boxes(op, bs):
    if op in ("union", "xor", "hull"):
        return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)
    if op == "intersection":
        return np.max([b[0] for b in bs], axis=0), np.min([b[1] for b in bs], axis=0)
    return bs[0]


def corner_box(m, lo, hi):
    corners = [m[:3, :3] @ np.where([(i >> k) & 1 for k in range(3)], hi, lo) + m[:3, 3] for i in range(8)]
    return np.min(corners, axis=0), np.max(corners, axis=0)


def revolve_setup(p):
    """(tree at x >= 0, flipped, angle) of a rotate_extrude's parameters;
    raises on a shape across the axis (OpenSCAD's error)."""
    f = p["flat"]
    lo, hi = flat_x_range(f)
    if lo < 0 < hi:
        raise ValueError(f"all points for rotate_extrude() must have the same X coordinate sign ({lo:.2f} -> {hi:.2f})")
    return (flat_mirror(f), True) if hi <= 0 else (f, False)


def wedge_normals(angle, flip):
    """The outward normals of the half-spaces whose meet (up to 180
    degrees) or join cuts the turn from 0 to angle (from 180 on, flipped)."""
    sa, ca = sin_cos_deg(abs(angle))
    sg = -1.0 if angle < 0 else 1.0
    turn = -1.0 if flip else 1.0
    return [np.array([0.0, -sg, 0.0]) * turn, np.array([-sa, ca * sg, 0.0]) * turn]


def largest_stretch(A):
    """The largest singular value of a 2x2 matrix, as csgrt computes it."""
    (a, b), (c, d) = A
    f = a * a + b * b + c * c + d * d
    det = a * d - b * c
    return math.sqrt(0.5 * (f + math.sqrt(max(f * f - 4 * det * det, 0.0))))


def flat_inside(f, p):
    """Whether p is in a 2-D tree of polygons, ellipses and their
    combinations (None for any other part)."""
    if f[0] == "poly":
        return even_odd_inside(f[1], p)
    if f[0] == "ellipse":
        q = np.linalg.solve(f[1], np.asarray(p) - f[2])
        return q @ q <= 1.0
    if f[0] != "op" or not (len(f) == 3 or plain_op(f)):
        return None
    ins = [flat_inside(k, p) for k in f[2]]
    if any(i is None for i in ins):
        return None
    if f[1] == "union":
        return any(ins)
    if f[1] == "intersection":
        return all(ins)
    if f[1] == "difference":
        return ins[0] and not any(ins[1:])
    return None


def hull_polygon(f):
    """A 2-D hull of polygons, circles and their combinations as a polygon
    that frames as the hull does: the hull of the points of its children's
    boundaries that can be extreme along an axis or in distance from the
    origin (corners, points where two boundaries cross, each circle's
    points along the axes and farthest from the origin), those in the
    closed region (within 1e-9 of its size). None for other children (they
    frame by their boxes)."""
    pts = []
    for kid in f[2]:
        got = edges_and_circles(kid, lambda g: g[0] == "op" and len(g) == 3 and g[1] != "xor")
        if got is None or flat_inside(kid, np.zeros(2)) is None:
            return None
        segs, circles = got
        cand = [np.asarray(a, float) for a, _ in segs]
        for c, r in circles:
            cand += [c + r * np.array(v, float) for v in ((1, 0), (0, 1), (-1, 0), (0, -1))]
            if np.any(c):
                cand.append(c + r * c / np.linalg.norm(c))
        for i, (a, b) in enumerate(segs):
            a, b = np.asarray(a, float), np.asarray(b, float)
            d = b - a
            for p0, q0 in segs[i + 1 :]:
                e = np.asarray(q0, float) - p0
                den = d[0] * e[1] - d[1] * e[0]
                if den != 0:
                    w = np.asarray(p0, float) - a
                    u, v = (w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den
                    if 0 <= u <= 1 and 0 <= v <= 1:
                        cand.append(a + u * d)
            for c, r in circles:
                A, B, C = d @ d, 2 * (a - c) @ d, (a - c) @ (a - c) - r * r
                disc = B * B - 4 * A * C
                if A > 0 and disc >= 0:
                    cand += [a + u * d for u in ((-B - math.sqrt(disc)) / (2 * A), (-B + math.sqrt(disc)) / (2 * A)) if 0 <= u <= 1]
        for i, (c1, r1) in enumerate(circles):
            for c2, r2 in circles[i + 1 :]:
                dd = c2 - c1
                l = float(np.linalg.norm(dd))
                if 0 < l <= r1 + r2 and l >= abs(r1 - r2):
                    x = (r1 * r1 - r2 * r2 + l * l) / (2 * l)
                    h = math.sqrt(max(r1 * r1 - x * x, 0.0))
                    mid, perp = c1 + dd * x / l, np.array([-dd[1], dd[0]]) / l
                    cand += [mid + h * perp, mid - h * perp]
        size = max(float(np.abs(q).max()) for q in cand) if cand else 1.0
        eps = 1e-9 * max(size, 1e-300)
        dirs = [np.array([math.cos(t), math.sin(t)]) for t in 2 * math.pi * np.arange(16) / 16]
        pts += [q for q in cand if flat_inside(kid, q) or any(flat_inside(kid, q + eps * v) for v in dirs)]
    if len(pts) < 3:
        return None
    h = convex_hull_2d(np.array(pts))
    return ("poly", [np.asarray(h, float)]) if len(h) >= 3 else None


def is_circle(A):
    """Whether A maps the unit circle to a circle (as csgrt decides)."""
    x, y = A[:, 0], A[:, 1]
    r2 = x @ x
    return abs(x @ y) <= 1e-12 * r2 and abs(y @ y - r2) <= 1e-12 * r2


def cone_box(m, A, c, s, z0, h):
    """The exact box of the cone over the ellipse A x + c (z = z0) tapered
    by s to z0 + h, placed by m: the hull of its two ellipses."""
    L, t = m[:3, :3], m[:3, 3]
    out = []
    for k, z in ((1.0, z0), (s, z0 + h)):
        C = L @ np.array([k * c[0], k * c[1], z]) + t
        U, V = L @ np.array([k * A[0, 0], k * A[1, 0], 0.0]), L @ np.array([k * A[0, 1], k * A[1, 1], 0.0])
        e = np.sqrt(U**2 + V**2)
        out.append((C - e, C + e))
    return combine_boxes("union", out)


def extrusion_box(leaf):
    """The box of an extrusion, as csgrt frames it: the box of the solid
    each 2-D leaf sweeps (a prism's corners; a cone over an ellipse, a torus
    or an ellipsoid exactly), combined as the 2-D tree combines them."""
    m, p = leaf.matrix, leaf.params
    L, t = m[:3, :3], m[:3, 3]
    if leaf.kind == "linear_extrude" and twisted(p):
        # csgrt's box of a twisted or unevenly scaled prism: without twist,
        # each axis scaled at the top; with it, the disc of the farthest
        # vertex grown by the larger of 1 and each scale. A centred circle
        # is the cone it sweeps.
        h, z0, (sx, sy) = p["h"], p["z0"], p["scale2"]
        grow = np.array([max(1.0, sx), max(1.0, sy)])

        def rec(f):
            if f[0] == "op" and f[1] == "hull" and (hp := hull_polygon(f)) is not None:
                return rec(hp)
            if f[0] == "poly":
                pts = np.concatenate(f[1])
                if p["twist"] == 0:
                    lo, hi = pts.min(axis=0), pts.max(axis=0)
                    lo, hi = np.minimum(lo, lo * [sx, sy]), np.maximum(hi, hi * [sx, sy])
                else:
                    rho = float(np.max(np.hypot(pts[:, 0], pts[:, 1])))
                    lo, hi = -grow * rho, grow * rho
                return corner_box(m, np.array([lo[0], lo[1], z0]), np.array([hi[0], hi[1], z0 + h]))
            if f[0] == "ellipse":
                A, c = f[1], f[2]
                if sx == sy and (p["twist"] == 0 or is_circle(A) and not np.any(c)):
                    return cone_box(m, A, c, sx, z0, h)
                # As csgrt's twisted ellipse: its box, or the disc of its
                # farthest point |c| + the largest singular value.
                if p["twist"] == 0:
                    e = np.sqrt(A[:, 0] ** 2 + A[:, 1] ** 2)
                    lo, hi = c - e, c + e
                    lo, hi = np.minimum(lo, lo * [sx, sy]), np.maximum(hi, hi * [sx, sy])
                else:
                    rho = math.hypot(c[0], c[1]) + largest_stretch(A)
                    lo, hi = -grow * rho, grow * rho
                return corner_box(m, np.array([lo[0], lo[1], z0]), np.array([hi[0], hi[1], z0 + h]))
            return combine_boxes(f[1], [rec(k) for k in f[2]])

        return rec(p["flat"])
    if leaf.kind == "linear_extrude":
        h, z0, s = p["h"], p["z0"], p["scale"]

        def rec(f):
            if f[0] == "op" and f[1] == "hull" and (hp := hull_polygon(f)) is not None:
                return rec(hp)
            if f[0] == "framed":
                return corner_box(m, np.array([f[2][0], f[2][1], z0]), np.array([f[3][0], f[3][1], z0 + h]))
            if f[0] in ("poly", "curves"):
                if f[0] == "poly":
                    pts = np.concatenate(f[1])
                    lo, hi = pts.min(axis=0), pts.max(axis=0)
                else:
                    lo, hi = curve_extent(f)
                lo, hi = np.minimum(lo, lo * s), np.maximum(hi, hi * s)
                return corner_box(m, np.array([lo[0], lo[1], z0]), np.array([hi[0], hi[1], z0 + h]))
            if f[0] == "ellipse":
                return cone_box(m, f[1], f[2], s, z0, h)
            return combine_boxes(f[1], [rec(k) for k in f[2]])

        return rec(p.get("frame", p["flat"]))
    f, flip = revolve_setup(p)

    def rec(f):
        if f[0] == "op" and f[1] == "hull" and (hp := hull_polygon(f)) is not None:
            return rec(hp)
        if f[0] == "curves":
            # Wholly at x >= 0 (the axis rule): its exact box, turned.
            lo, hi = curve_extent(f)
            r = max(hi[0], 0.0)
            return corner_box(m, np.array([-r, -r, lo[1]]), np.array([r, r, hi[1]]))
        if f[0] == "poly":
            loops = clip_right(f[1])
            if not loops:
                return EMPTY
            pts = np.concatenate(loops)
            r = max(pts[:, 0].max(), 0.0)
            return corner_box(m, np.array([-r, -r, pts[:, 1].min()]), np.array([r, r, pts[:, 1].max()]))
        if f[0] == "ellipse":
            A, c = f[1], f[2]
            ra, rz = abs(A[0, 0]), abs(A[1, 1])
            if c[0] + ra <= 0:
                return EMPTY
            st = Stmt("x", [], [], "", 0, 0)
            if c[0] == 0:
                lf = Leaf("sphere", dict(r=1.0), m @ affine(np.diag([ra, ra, rz]), [0, 0, c[1]]), {}, st)
            else:
                lf = Leaf("torus", dict(R=1.0, r=ra / c[0]), m @ affine(np.diag([c[0], c[0], c[0] * rz / ra]), [0, 0, c[1]]), {}, st)
            return leaf_box(lf)
        return combine_boxes(f[1], [rec(k) for k in f[2]])

    b = rec(f)
    if p["angle"] != 360:
        st = Stmt("x", [], [], "", 0, 0)
        hs = [leaf_box(Leaf("halfspace", dict(normal=n, offset=0.0), m, {}, st)) for n in wedge_normals(p["angle"], flip)]
        w = combine_boxes("intersection" if abs(p["angle"]) <= 180 else "union", hs)
        b = combine_boxes("intersection", [b, w])
    return b


def box(node):
    if node is None:
        return EMPTY
    if isinstance(node, Leaf):
        return leaf_box(node)
    bs = [box(c) for c in node.children]
    if node.op == "union":
        return np.min([b[0] for b in bs], axis=0), np.max([b[1] for b in bs], axis=0)
    if node.op == "intersection":
        return np.max([b[0] for b in bs], axis=0), np.min([b[1] for b in bs], axis=0)
    return bs[0]


def bounded_boxes(scene):
    """The world boxes of the leaves that have finite ones (not a halfspace)."""
    boxes = [leaf_box(x) for x in scene.leaves]
    return [b for b in boxes if np.all(np.isfinite(b[0])) and np.all(np.isfinite(b[1]))]


def bounded_box(scene, default=EMPTY):
    """The union of [`bounded_boxes`], or `default` when there are none."""
    boxes = bounded_boxes(scene)
    if not boxes:
        return default
    return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)


def framing_box(scene):
    lo, hi = box(scene.root)
    if np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) or np.any(lo > hi):
        return lo, hi
    return bounded_box(scene)


def framing(scene, width, height, fov=30.0, fill=0.9):
    lo, hi = framing_box(scene)
    if np.any(lo > hi) or not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        lo, hi = -np.ones(3), np.ones(3)
    center = (lo + hi) / 2
    ax, az = math.radians(55), math.radians(25)
    back = np.array([math.sin(ax) * math.sin(az), -math.sin(ax) * math.cos(az), math.cos(ax)])
    fwd = -back
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    tan_h = math.tan(math.radians(fov) / 2) * fill
    tan_v = tan_h * height / width
    dist = 0.5 * np.linalg.norm(hi - lo) * 1.01
    for i in range(8):
        c = np.where([(i >> k) & 1 for k in range(3)], hi, lo) - center
        depth = c @ fwd
        dist = max(dist, abs(c @ right) / tan_h - depth, abs(c @ up) / tan_v - depth)
    dist = max(dist, 1e-9)
    return center + back * dist, center, np.array([0.0, 0.0, 1.0]), fov


def read(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if path.endswith(".ray"):
        return read_ray(path, text)
    r = Reader(path)
    r.top(Parser(path, text).file())
    return r.scene
