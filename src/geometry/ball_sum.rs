//! A polytope rounded by a ball, P ⊕ B(r), written out as the union of
//! exact primitives: the commonest `minkowski()` (a box plus a ball) and
//! `hull()` (balls of one radius: capsules, rounded plates) become what
//! one would write by hand, and render at the speed of those primitives
//! rather than of support-function casts.
//!
//! The set of points within r of a convex polytope P is P itself, each
//! face pushed out by r (the prism over the face along its normal), each
//! edge's cylinder of radius r and each vertex's ball: a point within r of
//! P has its nearest point of P in a face's interior, an edge's or at a
//! vertex. P and the pushed faces are one closed mesh — the pushed faces
//! and, along each edge, the two walls that meet there — and the edges and
//! vertices are cylinders and spheres. A flat P (points in a plane) is the
//! slab |n·x| ≤ r over its polygon with the rounded rim; a segment, a
//! cylinder and two balls; a point, a ball.

use glam::{DAffine3, DMat3, DVec2, DVec3};

use crate::geometry::convex::ConvexPart;
use crate::geometry::mesh::{Mesh, MeshData};
use crate::geometry::{Aabb, Cone, Convex, Cuboid, Shape, Sphere};

use crate::plane::hull::{disc_hull, hull_indices_2d, MAX_HULL_POINTS};

/// The pieces of a rounded polytope, in the frame of its parts.
pub struct Pieces {
    pub parts: Vec<(Shape, DAffine3)>,
}

/// The points and radius when `hulls` (a Minkowski sum of hulls) is a
/// polytope plus a ball: a hull of polytopes (cubes, meshes, polygons'
/// prisms) summed with one ball, or one hull of balls of a single radius.
pub fn as_rounded(hulls: &[Vec<ConvexPart>]) -> Option<(Vec<DVec3>, f64)> {
    match hulls {
        [a, b] => {
            let (poly, ball) = match (ball_of(a), ball_of(b)) {
                (_, Some(ball)) => (a, ball),
                (Some(ball), None) => (b, ball),
                _ => return None,
            };
            let mut pts = Vec::new();
            for p in poly {
                vertices(p, &mut pts)?;
                if pts.len() > 8 * MAX_HULL_POINTS {
                    return None;
                }
            }
            Some((pts.into_iter().map(|p| p + ball.0).collect(), ball.1))
        }
        [a] if a.len() >= 2 => {
            let balls: Vec<(DVec3, f64)> = a
                .iter()
                .map(|p| ball_of(std::slice::from_ref(p)))
                .collect::<Option<_>>()?;
            let r = balls[0].1;
            balls
                .iter()
                .all(|b| (b.1 - r).abs() <= super::coaxial::EXPORT_ROUNDING * r)
                .then(|| (balls.iter().map(|b| b.0).collect(), r))
        }
        _ => None,
    }
}

/// One hull of balls whose centres lie on one line — two balls always do:
/// OpenSCAD's tapered capsule, `hull() { sphere(5); translate([16, 0, 0])
/// sphere(2); }` — as exact pieces. The set is turned about that line, so
/// its section through the line is the hull of the balls' discs there:
/// the discs on its boundary, and between two neighbours along the line
/// the trapezoid under their common tangent (a boundary disc's part
/// beyond its tangent points is its own). Turned: those balls, and
/// between neighbours the frustum from one tangent circle to the other —
/// for discs of radii r₁, r₂ whose centres are d apart, with k = (r₁ −
/// r₂)/d, the tangent circle of each lies r·k along the line from its
/// centre, of radius r·√(1 − k²). `None` for anything else, or centres
/// off the line by more than 10⁻¹² of the set's size.
pub fn as_ball_chain(hulls: &[Vec<ConvexPart>]) -> Option<Pieces> {
    let [parts] = hulls else { return None };
    if parts.len() < 2 || parts.len() > MAX_HULL_POINTS {
        return None;
    }
    let balls: Vec<(DVec3, f64)> = parts.iter().map(ball).collect::<Option<_>>()?;
    if balls
        .iter()
        .any(|b| !(b.1 > 0.0 && b.0.is_finite() && b.1.is_finite()))
    {
        return None;
    }
    // The line: from the centre farthest from the first to the one
    // farthest from that.
    let farthest = |from: DVec3| {
        balls
            .iter()
            .map(|b| b.0)
            .max_by(|p, q| (*p - from).length().total_cmp(&(*q - from).length()))
            .unwrap_or(from)
    };
    let c0 = farthest(balls[0].0);
    let c1 = farthest(c0);
    let length = (c1 - c0).length();
    let radius = balls.iter().map(|b| b.1).fold(0.0, f64::max);
    let tol = 1e-12 * (length + radius + c0.abs().max_element());
    let mut out = Pieces { parts: Vec::new() };
    if length <= tol {
        let (c, r) = balls
            .iter()
            .copied()
            .max_by(|p, q| p.1.total_cmp(&q.1))
            .unwrap_or(balls[0]);
        out.ball(c, r);
        return Some(out);
    }
    let u = (c1 - c0) / length;
    if balls
        .iter()
        .any(|b| (b.0 - c0).reject_from_normalized(u).length() > tol)
    {
        return None;
    }
    let discs: Vec<(DVec2, f64)> = balls
        .iter()
        .map(|&(c, r)| (DVec2::new((c - c0).dot(u), 0.0), r))
        .collect();
    let (_, mut on) = disc_hull(&discs)?;
    on.sort_by(|&a, &b| discs[a].0.x.total_cmp(&discs[b].0.x));
    on.dedup();
    for &i in &on {
        out.ball(balls[i].0, balls[i].1);
    }
    for w in on.windows(2) {
        let ((ci, ri), (cj, rj)) = (balls[w[0]], balls[w[1]]);
        let d = discs[w[1]].0.x - discs[w[0]].0.x;
        let k = (ri - rj) / d;
        // (Neighbours on the boundary have a band between them unless one
        // holds the other, touching it from inside.)
        if d > 0.0 && k.abs() < 1.0 {
            let c = if crate::mutant::active("ball_chain_untangent") {
                1.0
            } else {
                (1.0 - k * k).sqrt()
            };
            out.frustum(ci + u * (ri * k), cj + u * (rj * k), ri * c, rj * c);
        }
    }
    Some(out)
}

/// A hull that is one ball (a sphere under a uniform scale): its centre
/// and radius.
pub fn ball_of(hull: &[ConvexPart]) -> Option<(DVec3, f64)> {
    let [p] = hull else { return None };
    ball(p)
}

/// A part that is a ball (a sphere under a rotation and a uniform scale,
/// within [`super::coaxial::EXPORT_ROUNDING`]): its centre and radius.
pub fn ball(p: &ConvexPart) -> Option<(DVec3, f64)> {
    if !matches!(p.shape, Shape::Sphere(_)) {
        return None;
    }
    let m = p.to_world.matrix3;
    let g = m.transpose() * m;
    let r2 = (g.x_axis.x + g.y_axis.y + g.z_axis.z) / 3.0;
    let off = (g - DMat3::from_diagonal(DVec3::splat(r2))).to_cols_array();
    off.iter()
        .all(|x| x.abs() <= super::coaxial::EXPORT_ROUNDING * r2)
        .then(|| (p.to_world.translation, r2.sqrt()))
}

/// The placed vertices of a polytope part; `None` for a curved one.
fn vertices(p: &ConvexPart, out: &mut Vec<DVec3>) -> Option<()> {
    let m = &p.to_world;
    match &p.shape {
        Shape::Cuboid(c) => {
            let lo = crate::geometry::cuboid::low(c.centered);
            for i in 0..8 {
                let pick = |b: usize| if i & b != 0 { 1.0 } else { lo };
                out.push(m.transform_point3(DVec3::new(pick(1), pick(2), pick(4))));
            }
        }
        Shape::Mesh(mesh) => {
            if mesh.data.verts.len() > 8 * MAX_HULL_POINTS {
                return None;
            }
            out.extend(mesh.data.verts.iter().map(|&v| m.transform_point3(v)));
        }
        Shape::Prism(q) if !q.region.curved() => {
            let z = q.z_lo();
            for l in &q.region.outlines.loops {
                for &v in l {
                    out.push(m.transform_point3(v.extend(z)));
                    out.push(m.transform_point3((v * q.top).extend(z + 1.0)));
                }
            }
        }
        _ => return None,
    }
    Some(())
}

/// P ⊕ B(r) for the hull P of `pts`, as pieces; `None` past
/// [`MAX_HULL_POINTS`] distinct points.
pub fn pieces(pts: &[DVec3], r: f64) -> Option<Pieces> {
    pieces_beside(pts, r, &|_| false)
}

/// [`pieces`], less each face's prism, edge's cylinder and corner's ball
/// of a solid P whose face, edge or corner (by its points) `covered`
/// says lies in another polytope whose sum with the same ball is written
/// out already: that piece, every point within r of the face, edge or
/// corner, lies in that sum (for the union of several polytopes' sums:
/// [`Cells`]).
pub fn pieces_beside(pts: &[DVec3], r: f64, covered: &dyn Fn(&[DVec3]) -> bool) -> Option<Pieces> {
    let mut pts: Vec<DVec3> = pts.to_vec();
    pts.sort_by(|a, b| {
        a.to_array()
            .partial_cmp(&b.to_array())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    pts.dedup();
    if pts.len() > MAX_HULL_POINTS || pts.is_empty() {
        return None;
    }
    let scale = pts
        .iter()
        .fold(0.0f64, |s, p| s.max((*p - pts[0]).abs().max_element()));
    let tol = 1e-12 * scale.max(pts.iter().fold(0.0f64, |s, p| s.max(p.abs().max_element())));
    let mut out = Pieces { parts: Vec::new() };
    match span(&pts, tol) {
        Span::Point => out.ball(pts[0], r),
        Span::Segment(a, b) => out.capsule(a, b, r),
        Span::Plane(n) => {
            let poly = plane_hull(&pts, pts[0], n, tol);
            out.slab(&poly, n, r);
        }
        Span::Solid => out.solid(&pts, r, tol, covered),
    }
    Some(out)
}

/// What the points span.
pub enum Span {
    Point,
    Segment(DVec3, DVec3),
    /// A plane, by its normal.
    Plane(DVec3),
    Solid,
}

/// What `pts` (not empty) span, within `tol`: a segment by its two
/// extremes, a plane by its normal.
pub fn span(pts: &[DVec3], tol: f64) -> Span {
    let far = |from: &dyn Fn(DVec3) -> f64| {
        pts.iter()
            .copied()
            .max_by(|a, b| from(*a).total_cmp(&from(*b)))
            .expect("points")
    };
    let p0 = pts[0];
    let p1 = far(&|p| (p - p0).length());
    if (p1 - p0).length() <= tol {
        return Span::Point;
    }
    let dir = (p1 - p0).normalize();
    let p2 = far(&|p| (p - p0).reject_from_normalized(dir).length());
    if (p2 - p0).reject_from_normalized(dir).length() <= tol {
        let along = |p: DVec3| (p - p0).dot(dir);
        let a = far(&|p| -along(p));
        return Span::Segment(a, far(&|p| along(p)));
    }
    let n = (p1 - p0).cross(p2 - p0).normalize();
    let p3 = far(&|p| (p - p0).dot(n).abs());
    if (p3 - p0).dot(n).abs() <= tol {
        return Span::Plane(n);
    }
    Span::Solid
}

#[cfg(test)]
impl Pieces {
    /// Whether world point `p` lies in one of the pieces.
    pub(crate) fn has_point(&self, p: DVec3) -> bool {
        self.parts
            .iter()
            .any(|(s, m)| s.contains(m.inverse().transform_point3(p)))
    }

    /// Checks the pieces against the hull of points `pts` sampled on the
    /// solid's surface, which lies inside the solid and within `margin` of
    /// it: of `tries` random points about it, one inside the sampled hull
    /// must be in a piece, one farther than `margin` outside it in none
    /// (`what` names the set in a failure). The counts of points inside
    /// and outside that were checked.
    pub(crate) fn check_sampled_hull(
        &self,
        pts: &[DVec3],
        margin: f64,
        tries: usize,
        rnd: &mut impl FnMut() -> f64,
        what: &str,
    ) -> (usize, usize) {
        let (v, t) = crate::geometry::quickhull::hull(pts, 1e-9).unwrap();
        let planes: Vec<(DVec3, f64)> = t
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|i| v[i as usize]);
                let nrm = (b - a).cross(c - a).normalize();
                (nrm, nrm.dot(a))
            })
            .collect();
        let (bmin, bmax) = v
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), &p| {
                (a.min(p), b.max(p))
            });
        let (mut inside, mut outside) = (0, 0);
        for _ in 0..tries {
            let p = bmin - DVec3::ONE
                + (bmax - bmin + DVec3::splat(2.0)) * DVec3::new(rnd(), rnd(), rnd());
            let far = planes
                .iter()
                .map(|(nrm, d)| nrm.dot(p) - d)
                .fold(f64::NEG_INFINITY, f64::max);
            if far < -1e-9 {
                inside += 1;
                assert!(
                    self.has_point(p),
                    "{what}: {p} in the sampled hull, in no piece"
                );
            } else if far > margin {
                outside += 1;
                assert!(
                    !self.has_point(p),
                    "{what}: {p} {far} outside the hull, in a piece"
                );
            }
        }
        (inside, outside)
    }
}

impl Pieces {
    fn ball(&mut self, c: DVec3, r: f64) {
        let m =
            DAffine3::from_scale_rotation_translation(DVec3::splat(r), glam::DQuat::IDENTITY, c);
        self.parts.push((Shape::Sphere(Sphere), m));
    }

    /// The cylinder of radius r about segment ab, without its ends' balls.
    fn cylinder(&mut self, a: DVec3, b: DVec3, r: f64) {
        self.frustum(a, b, r, r);
    }

    /// The frustum about segment ab, of radius ra at a and rb at b (ra > 0).
    fn frustum(&mut self, a: DVec3, b: DVec3, ra: f64, rb: f64) {
        let z = (b - a).normalize();
        let helper = if z.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
        let x = helper.cross(z).normalize();
        let y = z.cross(x);
        let m = DAffine3::from_mat3_translation(DMat3::from_cols(x * ra, y * ra, b - a), a);
        let cone = Cone {
            r0: 1.0,
            r1: rb / ra,
            centered: false,
        };
        self.parts.push((Shape::Cone(cone), m));
    }

    fn capsule(&mut self, a: DVec3, b: DVec3, r: f64) {
        self.cylinder(a, b, r);
        self.ball(a, r);
        self.ball(b, r);
    }

    /// A closed mesh piece of these vertices and outward triangles.
    pub fn mesh(&mut self, verts: Vec<DVec3>, tris: Vec<[u32; 3]>) {
        let data = std::sync::Arc::new(MeshData::new(verts, tris));
        self.parts
            .push((Shape::Mesh(Mesh { data }), DAffine3::IDENTITY));
    }

    /// A flat convex polygon (in order) with normal n: the slab |n·x| ≤ r
    /// over it and its rim's capsules.
    fn slab(&mut self, poly: &[DVec3], n: DVec3, r: f64) {
        self.prism(
            poly.iter().map(|&p| p + n * r).collect(),
            poly.iter().map(|&p| p - n * r).collect(),
        );
        for i in 0..poly.len() {
            self.capsule_rim(poly[i], poly[(i + 1) % poly.len()], r);
        }
    }

    /// The closed mesh between a convex polygon `top` (counter-clockwise
    /// seen from outside) and `bottom`, the same polygon moved.
    pub fn prism(&mut self, top: Vec<DVec3>, bottom: Vec<DVec3>) {
        let k = top.len() as u32;
        let mut verts = top;
        verts.extend(bottom);
        let mut tris = Vec::new();
        for i in 1..k - 1 {
            tris.push([0, i, i + 1]);
            tris.push([k, k + i + 1, k + i]);
        }
        for i in 0..k {
            let j = (i + 1) % k;
            tris.push([i, k + i, k + j]);
            tris.push([i, k + j, j]);
        }
        self.mesh(verts, tris);
    }

    /// An edge of a rim: its cylinder and its first end's ball (each
    /// vertex is the first end of one edge).
    fn capsule_rim(&mut self, a: DVec3, b: DVec3, r: f64) {
        self.cylinder(a, b, r);
        self.ball(a, r);
    }

    /// A solid hull: its faces ([`hull_faces`]), the polytope P, each
    /// face's prism pushed out by r from it (convex pieces, clipped by
    /// their planes, where P with its faces pushed out is one mesh that is
    /// not), and the edges' and vertices' cylinders and balls.
    fn solid(&mut self, pts: &[DVec3], r: f64, tol: f64, covered: &dyn Fn(&[DVec3]) -> bool) {
        let mut tris: Vec<[u32; 3]> = Vec::new();
        let mut edges: Vec<(usize, usize)> = Vec::new();
        let mut corners: Vec<usize> = Vec::new();
        for (n, ids) in hull_faces(pts, tol) {
            let k = ids.len();
            for i in 1..k - 1 {
                tris.push([ids[0] as u32, ids[i] as u32, ids[i + 1] as u32]);
            }
            let face: Vec<DVec3> = ids.iter().map(|&q| pts[q]).collect();
            if !covered(&face) {
                self.prism(face.iter().map(|&p| p + n * r).collect(), face);
            }
            for i in 0..k {
                let (a, b) = (ids[i], ids[(i + 1) % k]);
                let e = (a.min(b), a.max(b));
                if !edges.contains(&e) {
                    edges.push(e);
                }
                if !corners.contains(&a) {
                    corners.push(a);
                }
            }
        }
        // P itself, under the prisms: only the hull's own points are the
        // mesh's (the others are left unused and dropped by the mesh's
        // renumbering).
        self.mesh(pts.to_vec(), tris);
        for (a, b) in edges {
            if !covered(&[pts[a], pts[b]]) {
                self.cylinder(pts[a], pts[b], r);
            }
        }
        for c in corners {
            if !covered(&[pts[c]]) {
                self.ball(pts[c], r);
            }
        }
    }
}

/// Convex polytopes, each by the planes of its faces, in the order their
/// sums with one ball are written out: the sum of a union of polytopes
/// with a ball is the union of their sums, and a piece of a later sum (a
/// face's prism, an edge's cylinder, a corner's ball) whose face, edge or
/// corner lies in an earlier polytope lies in that one's sum, and is left
/// out ([`pieces_beside`]). Only earlier ones: the earliest sum that
/// takes in a point keeps every piece near it, so no two sums leave a
/// piece out for each other. A union of cells cut from one solid loses
/// the prisms, cylinders and balls of the faces, edges and corners it
/// shares inside.
pub struct Cells {
    /// None for a cell that is not a solid polytope plus the ball.
    cells: Vec<Option<Cell>>,
    /// The cells by where they lie: a grid of about one bucket a cell
    /// over their box, each bucket the cells whose box (grown by its
    /// planes' thickness) meets it, in order. A point is asked of its
    /// bucket's cells alone: a cell that holds it meets that bucket, and a
    /// piece kept because a cell was not asked is only a piece more.
    grid: Grid,
}

/// A convex polytope's face planes (outward unit normal, offset) and
/// their thickness, and its box grown by that.
struct Cell {
    planes: Vec<(DVec3, f64)>,
    tol: f64,
    bounds: Aabb,
}

/// Buckets of cells over a box, `size` along each axis.
struct Grid {
    bounds: Aabb,
    size: usize,
    buckets: Vec<Vec<u32>>,
}

impl Grid {
    /// The bucket's coordinates along each axis of a point (clamped).
    fn at(&self, p: DVec3) -> [usize; 3] {
        let span = (self.bounds.max - self.bounds.min).max(DVec3::splat(f64::MIN_POSITIVE));
        let u = (p - self.bounds.min) / span * self.size as f64;
        [u.x, u.y, u.z].map(|v| (v.max(0.0) as usize).min(self.size - 1))
    }

    fn index(&self, [x, y, z]: [usize; 3]) -> usize {
        (z * self.size + y) * self.size + x
    }
}

impl Cells {
    /// The cells of polytopes with these corners (`None`: not a
    /// polytope summed with the ball; it holds nothing).
    pub fn new(cells: &[Option<&[DVec3]>]) -> Cells {
        let cell = |pts: &[DVec3]| {
            let bounds = pts.iter().fold(Aabb::EMPTY, |b, p| b.include(*p));
            // `polytope::points_tolerance`, of the box found here once.
            let tol = crate::geometry::polytope::plane_tolerance(&bounds);
            if !matches!(span(pts, tol), Span::Solid) {
                return None;
            }
            let faces = hull_faces(pts, tol);
            Some(Cell {
                planes: faces
                    .iter()
                    .map(|(n, ids)| (*n, n.dot(pts[ids[0]])))
                    .collect(),
                tol,
                bounds: Aabb {
                    min: bounds.min - DVec3::splat(tol),
                    max: bounds.max + DVec3::splat(tol),
                },
            })
        };
        let cells: Vec<Option<Cell>> = cells.iter().map(|c| c.and_then(cell)).collect();
        let all = cells
            .iter()
            .flatten()
            .fold(Aabb::EMPTY, |b, c| b.union(&c.bounds));
        let size = (cells.len() as f64).cbrt().ceil().clamp(1.0, 64.0) as usize;
        let mut grid = Grid {
            bounds: all,
            size,
            buckets: vec![Vec::new(); size * size * size],
        };
        for (k, c) in cells.iter().enumerate() {
            let Some(c) = c else { continue };
            let (lo, hi) = (grid.at(c.bounds.min), grid.at(c.bounds.max));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let i = grid.index([x, y, z]);
                        grid.buckets[i].push(k as u32);
                    }
                }
            }
        }
        Cells { cells, grid }
    }

    /// Whether every point of `pts` lies in one cell before cell `k`.
    pub fn earlier_holds(&self, k: usize, pts: &[DVec3]) -> bool {
        let Some(&first) = pts.first() else {
            return false;
        };
        let bucket = &self.grid.buckets[self.grid.index(self.grid.at(first))];
        bucket
            .iter()
            .take_while(|&&j| (j as usize) < k)
            .filter_map(|&j| self.cells[j as usize].as_ref())
            .any(|c| {
                pts.iter().all(|p| {
                    c.bounds.min.cmple(*p).all()
                        && c.bounds.max.cmpge(*p).all()
                        && c.planes.iter().all(|(n, h)| n.dot(*p) - h <= c.tol)
                })
            })
    }
}

/// The faces of the hull of `pts` (spanning a volume): each plane through
/// three of the points with every point on one side of it (within `tol`),
/// as its outward unit normal and the points on it in order
/// counter-clockwise about the normal (points on an edge left out).
pub fn hull_faces(pts: &[DVec3], tol: f64) -> Vec<(DVec3, Vec<usize>)> {
    let mut faces: Vec<(DVec3, Vec<usize>)> = Vec::new();
    let m = pts.len();
    for i in 0..m {
        for j in i + 1..m {
            for k in j + 1..m {
                let c = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
                let Some(n) = c.try_normalize() else { continue };
                if c.length() <= tol * (pts[j] - pts[i]).length().max((pts[k] - pts[i]).length()) {
                    continue;
                }
                let side = |p: DVec3| (p - pts[i]).dot(n);
                let (lo, hi) = pts.iter().fold((0.0f64, 0.0f64), |(l, h), &p| {
                    (l.min(side(p)), h.max(side(p)))
                });
                let n = if hi <= tol {
                    n
                } else if lo >= -tol {
                    -n
                } else {
                    continue;
                };
                let on: Vec<usize> = (0..m)
                    .filter(|&q| (pts[q] - pts[i]).dot(n).abs() <= tol)
                    .collect();
                if !faces.iter().any(|f| f.1 == on) {
                    faces.push((n, on));
                }
            }
        }
    }
    faces
        .into_iter()
        .map(|(n, on)| {
            let local: Vec<DVec3> = on.iter().map(|&q| pts[q]).collect();
            let ring = plane_hull_indices(&local, local[0], n, tol);
            (n, ring.iter().map(|&q| on[q]).collect())
        })
        .collect()
}

/// The convex polygon (counter-clockwise about n) of points in the plane
/// through `o` with normal `n`.
pub fn plane_hull(pts: &[DVec3], o: DVec3, n: DVec3, tol: f64) -> Vec<DVec3> {
    plane_hull_indices(pts, o, n, tol)
        .into_iter()
        .map(|i| pts[i])
        .collect()
}

/// Andrew's monotone chain in the plane's coordinates; points on an edge
/// (within `tol`) are left out.
fn plane_hull_indices(pts: &[DVec3], o: DVec3, n: DVec3, tol: f64) -> Vec<usize> {
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let q: Vec<DVec2> = pts
        .iter()
        .map(|&p| DVec2::new((p - o).dot(u), (p - o).dot(v)))
        .collect();
    hull_indices_2d(&q, tol)
}

/// A hull of straight cylinders with parallel axes over one range along
/// them, circular across (a slot, a plate rounded at its corners): the
/// prism of the hull of their circles, as the prism of its polygon and
/// the cylinders on its boundary.
pub fn as_cylinders(hulls: &[Vec<ConvexPart>]) -> Option<Pieces> {
    let [parts] = hulls else { return None };
    let mut axis: Option<DVec3> = None;
    let mut range: Option<(f64, f64)> = None;
    let mut discs = Vec::new();
    for p in parts {
        let c = super::coaxial::placed_cone(p)?;
        if c.r_bottom != c.r_top || c.r_bottom <= 0.0 {
            return None;
        }
        let a = *axis.get_or_insert(c.axis);
        if c.axis.cross(a).length() > 1e-12 {
            return None;
        }
        let (b, t) = (c.bottom, c.top);
        let (lo, hi) = (b.dot(a).min(t.dot(a)), b.dot(a).max(t.dot(a)));
        let (rlo, rhi) = *range.get_or_insert((lo, hi));
        let tol = 1e-12 * (rlo.abs().max(rhi.abs()) + (rhi - rlo));
        if (lo - rlo).abs() > tol || (hi - rhi).abs() > tol {
            return None;
        }
        discs.push((b, c.r_bottom));
    }
    let (a, (lo, hi)) = (axis?, range?);
    let u = a.any_orthonormal_vector();
    let v = a.cross(u);
    let flat: Vec<(DVec2, f64)> = discs
        .iter()
        .map(|&(b, r)| (DVec2::new(b.dot(u), b.dot(v)), r))
        .collect();
    let (poly, on) = disc_hull(&flat)?;
    let at = |p: DVec2, s: f64| u * p.x + v * p.y + a * s;
    let mut out = Pieces { parts: Vec::new() };
    if poly.len() >= 3 {
        let k = poly.len() as u32;
        let mut verts: Vec<DVec3> = poly.iter().map(|&p| at(p, lo)).collect();
        verts.extend(poly.iter().map(|&p| at(p, hi)));
        let mut tris = Vec::new();
        for i in 1..k - 1 {
            tris.push([0, i + 1, i]);
            tris.push([k, k + i, k + i + 1]);
        }
        for i in 0..k {
            let j = (i + 1) % k;
            tris.push([i, j, k + j]);
            tris.push([i, k + j, k + i]);
        }
        out.mesh(verts, tris);
    }
    for i in on {
        let (c, r) = flat[i];
        let m = DAffine3::from_mat3_translation(
            DMat3::from_cols(u * r, v * r, a * (hi - lo)),
            at(c, lo),
        );
        let cone = Cone {
            r0: 1.0,
            r1: 1.0,
            centered: false,
        };
        out.parts.push((Shape::Cone(cone), m));
    }
    Some(out)
}

/// The most triangles of a mesh rounded by a ball (three pieces each).
pub const MAX_ROUNDED_TRIANGLES: usize = 20_000;

/// A mesh of any shape (placed by `m`) plus a ball of radius r about the
/// origin: the mesh itself, each triangle's slab |n·x| ≤ r over it, each
/// edge's cylinder and each vertex's ball — A ⊕ B = A ∪ (∂A ⊕ B) for a
/// solid A and a convex B (a point of the sum whose ball misses A's
/// boundary has its ball, hence its centre, in A), and a triangle plus a
/// ball is its slab with its rim's capsules. `None` past
/// [`MAX_ROUNDED_TRIANGLES`].
pub fn mesh_rounded(mesh: &Mesh, m: DAffine3, r: f64) -> Option<Pieces> {
    let d = &mesh.data;
    if d.tris.len() > MAX_ROUNDED_TRIANGLES {
        return None;
    }
    let v = placed_corners(mesh, m);
    let mut out = Pieces { parts: Vec::new() };
    out.parts.push((Shape::Mesh(mesh.clone()), m));
    let mut edges = std::collections::BTreeSet::new();
    let mut used = std::collections::BTreeSet::new();
    for t in &d.tris {
        let [a, b, c] = t.map(|i| v[i as usize]);
        for (x, y) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            edges.insert((x.min(y), x.max(y)));
        }
        used.extend(t.iter().copied());
        let Some(n) = (b - a).cross(c - a).try_normalize() else {
            continue;
        };
        let verts = vec![
            a + n * r,
            b + n * r,
            c + n * r,
            a - n * r,
            b - n * r,
            c - n * r,
        ];
        let tris = vec![
            [0, 1, 2],
            [3, 5, 4],
            [0, 3, 4],
            [0, 4, 1],
            [1, 4, 5],
            [1, 5, 2],
            [2, 5, 3],
            [2, 3, 0],
        ];
        out.mesh(verts, tris);
    }
    for (x, y) in edges {
        if v[x as usize] != v[y as usize] {
            out.cylinder(v[x as usize], v[y as usize], r);
        }
    }
    for i in used {
        out.ball(v[i as usize], r);
    }
    Some(out)
}

/// The most triangles of a mesh summed with a convex set other than a
/// ball (one support-function piece each).
pub const MAX_SUMMED_TRIANGLES: usize = 5_000;

/// A mesh (placed by `m`) that is not convex plus the union of the convex
/// sets `sets` (each a sum of hulls), as pieces. Where the mesh is cut into
/// fewer convex cells ([`mesh_cells`](super::mesh_cells::mesh_cells)) than
/// half its triangles, each cell plus each set B; else, for each B, the
/// mesh moved by one point b of B, and each triangle plus B — A ⊕ B =
/// (A + b) ∪ (∂A ⊕ B) for a convex B (on the segment from b to any other
/// point of B, a point of the sum leaves A + b only across A's boundary).
/// Each piece is convex: written out where B is a polytope, else known by
/// its support function. `None` past [`MAX_SUMMED_TRIANGLES`] triangles
/// in all.
pub fn mesh_plus(mesh: &Mesh, m: DAffine3, sets: &[Vec<Vec<ConvexPart>>]) -> Option<Pieces> {
    if mesh.data.tris.len() * sets.len() > MAX_SUMMED_TRIANGLES {
        return None;
    }
    let v = placed_corners(mesh, m);
    let tris = &mesh.data.tris;
    let tol = super::polytope::points_tolerance(&v);
    let cells = super::mesh_cells::mesh_cells(&v, tris, tol, tris.len() / 2);
    Some(mesh_pieces_plus(mesh, m, &v, cells.as_deref(), sets))
}

/// The corners of `mesh` placed by `m`.
fn placed_corners(mesh: &Mesh, m: DAffine3) -> Vec<DVec3> {
    mesh.data
        .verts
        .iter()
        .map(|&p| m.transform_point3(p))
        .collect()
}

/// [`mesh_plus`] of the mesh with corners `v` (placed by `m`), by its
/// `cells`, or by its triangles where there are none.
fn mesh_pieces_plus(
    mesh: &Mesh,
    m: DAffine3,
    v: &[DVec3],
    cells: Option<&[super::polytope::Polytope]>,
    sets: &[Vec<Vec<ConvexPart>>],
) -> Pieces {
    // A vertex as a part: a box shrunk to the point.
    let point = |p: DVec3| ConvexPart {
        shape: Shape::Cuboid(Cuboid { centered: false }),
        to_world: DAffine3 {
            matrix3: DMat3::ZERO,
            translation: p,
        },
    };
    let mut out = Pieces { parts: Vec::new() };
    for rest in sets.iter().filter(|r| !r.is_empty()) {
        if cells.is_none() {
            let b = Convex::new(rest.to_vec()).support_point(DVec3::X);
            out.parts
                .push((Shape::Mesh(mesh.clone()), DAffine3::from_translation(b) * m));
        }
        // Each piece of A (a cell, or a triangle of its surface) plus B.
        let mut add = |corners: Vec<DVec3>| {
            let mut hulls = vec![corners.into_iter().map(point).collect()];
            hulls.extend(rest.iter().cloned());
            // A convex piece plus polytopes is a polytope: written out
            // (its corners' sums hulled), not cast by GJK.
            match super::convex::polytope_sum(&hulls) {
                Some(mesh) => out.parts.push((Shape::Mesh(mesh), DAffine3::IDENTITY)),
                None => {
                    let (c, centre) = Convex::centred(hulls);
                    out.parts
                        .push((Shape::Convex(c), DAffine3::from_translation(centre)));
                }
            }
        };
        if let Some(cells) = cells {
            for cell in cells {
                add(cell.vertices());
            }
            continue;
        }
        for t in &mesh.data.tris {
            add(t.iter().map(|&i| v[i as usize]).collect());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A union of polytopes summed with one ball, each sum less the pieces
    /// whose face, edge or corner an earlier polytope holds ([`Cells`]),
    /// is the union of the whole sums: at random points about them, for a
    /// box cut along a diagonal plane (cells sharing a face, edges and
    /// the box's corners), a ring of twelve wedges (as a cylinder's
    /// difference is cut) and two boxes that overlap; and it has fewer
    /// pieces.
    #[test]
    fn a_union_of_rounded_cells_keeps_each_shared_piece_once() {
        let mut rnd = crate::plane::tests::uniform(83);
        let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let boxed = |lo: DVec3, hi: DVec3| -> Vec<DVec3> {
            (0..8)
                .map(|i| {
                    let pick = |b: usize, l: f64, h: f64| if i & b != 0 { h } else { l };
                    v(
                        pick(1, lo.x, hi.x),
                        pick(2, lo.y, hi.y),
                        pick(4, lo.z, hi.z),
                    )
                })
                .collect()
        };
        let wedge = |k: usize| -> Vec<DVec3> {
            let a = |j: usize| std::f64::consts::TAU * j as f64 / 12.0;
            let mut out = Vec::new();
            for j in [k, k + 1] {
                for rad in [1.0, 1.6] {
                    for z in [0.0, 0.5] {
                        out.push(v(rad * a(j).cos(), rad * a(j).sin(), z));
                    }
                }
            }
            out
        };
        let sets: Vec<Vec<Vec<DVec3>>> = vec![
            // The unit box's corners with x ≥ y, and with x ≤ y.
            [1.0, -1.0]
                .map(|side| {
                    let unit = boxed(DVec3::ZERO, DVec3::ONE);
                    unit.into_iter()
                        .filter(|p| side * (p.x - p.y) >= 0.0)
                        .collect()
                })
                .to_vec(),
            (0..12).map(wedge).collect(),
            vec![
                boxed(v(0., 0., 0.), v(2., 1., 1.)),
                boxed(v(1., 0.5, 0.), v(3., 2., 1.5)),
            ],
        ];
        let r = 0.3;
        for cells in sets {
            let whole: Vec<Pieces> = cells.iter().map(|c| pieces(c, r).unwrap()).collect();
            let corners: Vec<Option<&[DVec3]>> = cells.iter().map(|c| Some(&c[..])).collect();
            let index = Cells::new(&corners);
            let kept: Vec<Pieces> = cells
                .iter()
                .enumerate()
                .map(|(k, c)| pieces_beside(c, r, &|f| index.earlier_holds(k, f)).unwrap())
                .collect();
            let count = |p: &[Pieces]| p.iter().map(|x| x.parts.len()).sum::<usize>();
            assert!(
                count(&kept) < count(&whole),
                "{} of {}",
                count(&kept),
                count(&whole)
            );
            let (lo, hi) = cells
                .iter()
                .flatten()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), &p| {
                    (a.min(p), b.max(p))
                });
            let (lo, hi) = (lo - DVec3::splat(r + 0.05), hi + DVec3::splat(r + 0.05));
            let mut inside = 0;
            for _ in 0..20_000 {
                let p = lo + (hi - lo) * v(rnd(), rnd(), rnd());
                let want = whole.iter().any(|w| w.has_point(p));
                let got = kept.iter().any(|w| w.has_point(p));
                assert_eq!(got, want, "{p}");
                inside += usize::from(want);
            }
            assert!(
                (2000..18_000).contains(&inside),
                "{inside} of 20000 in the sums"
            );
        }
        // Held within the rounding of the cell's planes, not a hair more.
        let unit = boxed(v(0., 0., 0.), v(1., 1., 1.));
        let index = Cells::new(&[Some(&unit[..]), None]);
        let (on, off) = (v(1.0, 0.3, 0.7), v(1.0 + 1e-8, 0.3, 0.7));
        assert!(index.earlier_holds(1, &[on, v(0.0, 1.0, 1.0)]));
        assert!(!index.earlier_holds(1, &[on, off]));
        assert!(!index.earlier_holds(0, &[on]), "a cell before the first");
    }

    /// Balls of several radii on a line, hulled: a point inside the hull
    /// of points sampled on the balls is in a piece, a point farther than
    /// the sampling's sagitta outside it in none — along random lines, with
    /// balls inside others and balls at one place among them.
    #[test]
    fn balls_on_a_line_hulled_are_their_sampled_hull() {
        let mut rnd = crate::plane::tests::uniform(47);
        let n = 3000;
        let (mut inside, mut outside) = (0, 0);
        for set in 0..40 {
            let dir = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
            let origin = DVec3::new(rnd(), rnd(), rnd()) * 20.0 - DVec3::splat(10.0);
            let mut balls: Vec<(DVec3, f64)> = (0..2 + set % 4)
                .map(|_| (origin + dir * (12.0 * rnd()), 0.3 + 3.0 * rnd()))
                .collect();
            if set % 5 == 0 {
                // One inside another, and one at another's centre.
                let (c, r) = balls[0];
                balls.push((c + dir * (0.3 * r), 0.5 * r));
                balls.push((balls[1].0, 0.4 * balls[1].1));
            }
            let parts: Vec<ConvexPart> = balls
                .iter()
                .map(|&(c, r)| ConvexPart {
                    shape: Shape::Sphere(Sphere),
                    to_world: DAffine3::from_scale_rotation_translation(
                        DVec3::splat(r),
                        glam::DQuat::from_rotation_arc(DVec3::Z, dir),
                        c,
                    ),
                })
                .collect();
            let pieces = as_ball_chain(&[parts]).unwrap_or_else(|| panic!("set {set}: no pieces"));
            let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
            let mut pts = Vec::new();
            for &(c, r) in &balls {
                for k in 0..n {
                    let z = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
                    let (a, w) = (golden * k as f64, (1.0 - z * z).sqrt());
                    pts.push(c + DVec3::new(w * a.cos(), w * a.sin(), z) * r);
                }
            }
            // The sampling's widest gap is about 2·√(4π/n) of a turn.
            let rmax = balls.iter().map(|b| b.1).fold(0.0, f64::max);
            let sagitta =
                rmax * (1.0 - (2.0 * (4.0 * std::f64::consts::PI / n as f64).sqrt()).cos());
            let (i, o) =
                pieces.check_sampled_hull(&pts, sagitta, 600, &mut rnd, &format!("set {set}"));
            (inside, outside) = (inside + i, outside + o);
        }
        assert!(
            inside > 3000 && outside > 3000,
            "{inside} inside, {outside} outside"
        );
    }

    /// An L-shaped prism (a mesh that is not convex) plus a box along
    /// the axes, summed cell by cell or triangle by triangle, is the union
    /// of its two boxes each grown by the box: at
    /// random points, in a piece exactly where in one of those (points
    /// within 10⁻⁹ of their sides left out), every piece written out (no
    /// support-function solid).
    #[test]
    fn an_l_plus_a_box_is_its_two_boxes_grown() {
        let mut rnd = crate::plane::tests::uniform(53);
        let mut counts = (0, 0);
        for round in 0..20 {
            let (w, d, a, b, h) = (
                4.0 + 4.0 * rnd(),
                4.0 + 4.0 * rnd(),
                1.0 + 2.0 * rnd(),
                1.0 + 2.0 * rnd(),
                1.0 + 3.0 * rnd(),
            );
            // The L: [0, w]×[0, b] and [0, a]×[0, d], h high.
            let floor = [[0.0, 0.0], [w, 0.0], [w, b], [a, b], [a, d], [0.0, d]];
            let mut verts: Vec<DVec3> = floor.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
            verts.extend(floor.iter().map(|p| DVec3::new(p[0], p[1], h)));
            let mut tris: Vec<[u32; 3]> = Vec::new();
            for q in [[0, 1, 2, 3], [0, 3, 4, 5]] {
                tris.push([q[0], q[2], q[1]]);
                tris.push([q[0], q[3], q[2]]);
                tris.push([q[0] + 6, q[1] + 6, q[2] + 6]);
                tris.push([q[0] + 6, q[2] + 6, q[3] + 6]);
            }
            for i in 0..6u32 {
                let j = (i + 1) % 6;
                tris.push([i, j, j + 6]);
                tris.push([i, j + 6, i + 6]);
            }
            let mesh = Mesh {
                data: std::sync::Arc::new(crate::geometry::mesh::MeshData::new(verts, tris)),
            };
            let lo = DVec3::new(rnd(), rnd(), rnd()) * 2.0 - DVec3::ONE;
            let size = DVec3::new(0.2 + rnd(), 0.2 + rnd(), 0.2 + rnd());
            let cube = ConvexPart {
                shape: Shape::Cuboid(Cuboid { centered: false }),
                to_world: DAffine3::from_scale_rotation_translation(
                    size,
                    glam::DQuat::IDENTITY,
                    lo,
                ),
            };
            let m = DAffine3::from_translation(DVec3::new(rnd(), rnd(), rnd()));
            let sets = [vec![vec![cube]]];
            // By its convex cells (2 or 3: fewer than half its 20 triangles),
            // and, every other round, by its triangles and itself moved.
            let pieces = if round % 2 == 0 {
                let pieces = mesh_plus(&mesh, m, &sets).expect("pieces");
                let cells = pieces.parts.len();
                assert!((2..=3).contains(&cells), "round {round}: {cells} cells");
                pieces
            } else {
                let v = placed_corners(&mesh, m);
                let pieces = mesh_pieces_plus(&mesh, m, &v, None, &sets);
                assert_eq!(pieces.parts.len(), 21, "round {round}: a piece a triangle");
                pieces
            };
            assert!(pieces
                .parts
                .iter()
                .all(|(s, _)| matches!(s, Shape::Mesh(_))));
            let o = m.translation;
            let grown = [
                (DVec3::ZERO, DVec3::new(w, b, h)),
                (DVec3::ZERO, DVec3::new(a, d, h)),
            ]
            .map(|(l, u)| (o + l + lo, o + u + lo + size));
            for _ in 0..2000 {
                let p = o + lo + DVec3::new(rnd() * 12.0, rnd() * 12.0, rnd() * 8.0) - 1.0;
                let margin = grown
                    .iter()
                    .map(|(l, u)| (p - *l).abs().min((*u - p).abs()).min_element())
                    .fold(f64::INFINITY, f64::min);
                if margin < 1e-9 {
                    continue;
                }
                let want = grown
                    .iter()
                    .any(|(l, u)| l.cmplt(p).all() && p.cmplt(*u).all());
                assert_eq!(pieces.has_point(p), want, "round {round}: {p}");
                tally(&mut counts, want);
            }
        }
        enough(counts);
    }

    /// A box rounded by a ball is its convex polytope, a prism on each of
    /// its 6 faces, 12 cylinders and 8 balls: at random points about
    /// turned boxes, in a piece exactly where within r of the box (the
    /// distance in closed form; points within 10⁻⁹ of the surface left
    /// out).
    #[test]
    fn a_box_rounded_is_seven_polytopes_twelve_cylinders_and_eight_balls() {
        let mut rnd = crate::plane::tests::uniform(61);
        let mut counts = (0, 0);
        for round in 0..20 {
            let half = DVec3::new(0.5 + 3.0 * rnd(), 0.5 + 3.0 * rnd(), 0.5 + 3.0 * rnd());
            let r = 0.1 + 2.0 * rnd();
            let turn = glam::DQuat::from_axis_angle(
                DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize(),
                6.0 * rnd(),
            );
            let centre = DVec3::new(rnd(), rnd(), rnd()) * 10.0 - DVec3::splat(5.0);
            let pts: Vec<DVec3> = (0..8)
                .map(|i| {
                    let s = DVec3::new(
                        if i & 1 == 0 { -1.0 } else { 1.0 },
                        if i & 2 == 0 { -1.0 } else { 1.0 },
                        if i & 4 == 0 { -1.0 } else { 1.0 },
                    );
                    centre + turn * (s * half)
                })
                .collect();
            let p = pieces(&pts, r).unwrap();
            let count = |name: &str| p.parts.iter().filter(|(s, _)| s.name() == name).count();
            assert_eq!(
                (count("polyhedron"), count("cylinder"), count("sphere")),
                (7, 12, 8)
            );
            for _ in 0..1000 {
                let local = (DVec3::new(rnd(), rnd(), rnd()) * 2.0 - DVec3::ONE)
                    * (half + DVec3::splat(r))
                    * 1.2;
                let q = centre + turn * local;
                let distance = (local.abs() - half).max(DVec3::ZERO).length();
                if (distance - r).abs() < 1e-9 {
                    continue;
                }
                let want = distance < r;
                assert_eq!(p.has_point(q), want, "round {round}: {q}");
                tally(&mut counts, want);
            }
        }
        enough(counts);
    }

    /// Counts a point checked, inside or outside.
    fn tally(counts: &mut (u32, u32), inside: bool) {
        if inside {
            counts.0 += 1;
        } else {
            counts.1 += 1;
        }
    }

    /// Whether enough points were checked on each side.
    fn enough((inside, outside): (u32, u32)) {
        assert!(
            inside > 3000 && outside > 3000,
            "{inside} inside, {outside} outside"
        );
    }

    #[test]
    fn balls_in_a_plane_make_a_slab_and_its_rim() {
        let pts = [
            DVec3::ZERO,
            DVec3::X * 4.0,
            DVec3::new(4.0, 3.0, 0.0),
            DVec3::Y * 3.0,
            DVec3::new(2.0, 1.0, 0.0),
        ];
        let p = pieces(&pts, 1.0).unwrap();
        let count = |name: &str| p.parts.iter().filter(|(s, _)| s.name() == name).count();
        assert_eq!(
            (count("polyhedron"), count("cylinder"), count("sphere")),
            (1, 4, 4)
        );
        let two = pieces(&[DVec3::ZERO, DVec3::Z * 5.0, DVec3::Z * 2.0], 1.0).unwrap();
        assert_eq!(two.parts.len(), 3);
    }
}
