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
background #ffffe5), sRGB-encoded as every colour a file gives (decoded
to linear values for shading, the 8-bit image encoded again); without
lights, an ambient term, a key light and two shadowless fills placed about
the camera (meaning.default_lights); without a camera, the frame of the scene's box from OpenSCAD's
default view direction (rotation [55, 0, 25]), the eye pulled back until
the box's eight corners lie in the central 90 % of a 30 degree view.

The scene's box, for that framing, is derived here the same way the
README's language reference states it: a leaf's exact world box (an
ellipsoid's or a disc's extent, a torus as circle + ball, a box's corners,
an axis-aligned halfspace bounded on one side), unions join boxes,
intersections cut them, a difference keeps its first child's; when that box
is unbounded (a floor), the union of the bounded leaves' boxes is framed.

Usage as a module: `read(path, width, height)` -> Scene.

The reader is split along its sections, one module each: bounds, display_list, dxf, meaning, plane, solids, svg, syntax, text.
"""

from .syntax import *  # noqa: F401,F403
from .meaning import *  # noqa: F401,F403
from .display_list import *  # noqa: F401,F403
from .bounds import *  # noqa: F401,F403
from .text import *  # noqa: F401,F403
from .plane import *  # noqa: F401,F403
from .solids import *  # noqa: F401,F403
from .dxf import *  # noqa: F401,F403
from .svg import *  # noqa: F401,F403
