"""The manifold3d oracle: does csgrt render what the file says?

For each scene the oracle reads the file itself (tools/oracle/scene/, its own
parser, sharing nothing with csgrt's Rust code), builds the same CSG tree
with manifold3d at several numbers of circular segments n, takes its own
camera, and compares with what csgrt outputs: the image and the hit mask of
a render at one sample a pixel, and `--trace-rays` answers (t and normal)
for the ray through every pixel centre of the oracle's camera plus a set of
random rays (seeded by the scene's file name) from all around the solid.

What is compared, everything in the verdict:

* hit/miss per pixel (csgrt's mask against the oracle's cast through the
  oracle's camera) and per ray;
* depth: |t_csgrt - t_mesh| within the depth bound (below) at every pixel
  and every ray, at every angle of incidence;
* normals: the angle between csgrt's normal and the mesh's within the
  normal bound (below);
* colour: every pixel whose surface is opaque and not reflective is shaded
  by the oracle with the seed's Phong model (slides 25-29: ka Ia C, then
  per light kd (N.L) C Il + ks (V.R)^ns Il, shadows from the mesh, the
  light dimmed by the kt of transparent blockers, each channel clamped and
  rounded to a byte) from the oracle's own materials and lights and csgrt's
  (already checked) hit point and normal; it must match csgrt's byte within
  2 levels. Where a light's shadow is ambiguous (the pixel's 3x3 neighbours
  disagree about it in the oracle, or N.L < 0.02) both answers are accepted.

A pixel can only disagree where the picture has an edge: the oracle's 3x3
neighbourhood holds a hit and a miss, or two surfaces (two leaves, or two
faces of one leaf: a cube's sides, a cylinder's caps and side; a hit
within the leaf's faceting distance of both a cap and a side is a crease
of its own, since the mesh may put it on either). Every
disagreeing pixel must be such an edge pixel, at every n; and the number of
disagreeing pixels and rays must not grow as n doubles (within 2 of grid
noise) and must shrink overall from the coarsest n to the finest, unless
it is already 2 or less. At the finest n, no random ray may be beyond its
depth or normal bound.

The bounds (per leaf, for the leaf the mesh ray hits; b = 1 - cos(pi/n)):

* faceting distance delta: the mesh lies within delta of the true surface,
  delta = k R b sigma_max (R the leaf's largest radius, sigma_max the
  largest singular value of its matrix; k = 1 for a cylinder or cone, whose
  mesh is an inscribed polygon; 3 for manifold's geodesic sphere, measured
  2.69; a torus adds its tube's and its sweep's bounds; cubes and
  halfspaces are exact, delta = 0);
* depth: a ray meeting the surface at angle theta (c = |cos theta|, from
  csgrt's normal) sees that offset as at most delta / c, and a surface of
  curvature radius R_c moved inward by delta is met at most sqrt(2 R_c
  delta) away even at grazing (the chord of the sphere of radius R_c), so

      |t_csgrt - t_mesh| <= min(2 delta / c, 2 sqrt(2 R delta)) + 1e-9 L

  (a factor 2 for the first-order estimates, L = |origin| + t the ray's
  length scale); the bound grows toward grazing and stays finite there;
* normal: a face whose vertices lie on the surface turns from the true
  normal by at most the facet angle: pi/n for a cylinder's or cone's side
  (the face spans 2 pi/n of azimuth, the normal at its middle), for the
  sphere the angular radius of the face, acos(1 - 3 b) (its plane lies
  within 3 b R), for a torus pi/n of sweep plus pi/n of tube. A linear map
  turns angles by at most its condition number kappa = sigma_max /
  sigma_min. The two normals are taken at two points of the surface: the
  exact hit and the mesh's, |t_csgrt - t_mesh| apart along the ray and
  within delta of the surface, so the true normal itself turns by at most
  (|dt| + delta) / rho between them, rho the world's smallest curvature
  radius there (sigma_min r / kappa for an object radius r: the sphere's
  r, the cone's radius at the hit, the torus's min(r, R - r)). Hence

      angle <= kappa * facet(n) + kappa (|dt| + delta) / (sigma_min r) + 1e-7.

A halfspace is unbounded; the mesh stands it in by a box 10^6 times the
scene's size, whose far faces lie far below one pixel from the horizon.

Usage: python -m tools.oracle.oracle [--csgrt BIN] [--size WxH] [--segments 64,128,256,512]
                 [--rays N] [--out DIR] [--check] [--table FILE] SCENE...
Exit status 1 when --check finds a scene that fails.
"""

from .bounds import *  # noqa: F401,F403
from .mesh import *  # noqa: F401,F403
from .cast import *  # noqa: F401,F403
from .ray_sets import *  # noqa: F401,F403
from .compare_side import *  # noqa: F401,F403
from .run import *  # noqa: F401,F403
