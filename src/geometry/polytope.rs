//! Convex polytopes by their faces, cut by planes: the certified
//! approximation of a combination that has no exact hull or Minkowski sum.
//!
//! A leaf becomes a union of convex polytopes within a distance `eps` of
//! it (its Hausdorff distance): a cube, a mesh that is convex, a straight
//! extrusion of polygons (one prism per triangle of its outline) exactly;
//! a sphere and a cylinder or cone as the polytope of points *on* their
//! surface whose faces stray from it by at most `eps` (for a unit circle
//! cut into n chords the gap is 1 − cos(π/n), carried into the world by
//! the transform's largest stretch σ; a sphere's faces are quads whose
//! half-diagonal spans at most √2·π/n). Intersections and differences are
//! then cut exactly, plane by plane: P ∖ Q for convex Q is the union of
//! P beyond each face of Q and within the faces before it — disjoint
//! convex pieces. So each piece's points lie within `eps` of the exact
//! solid wherever the faces meet it at a fair angle, and the hull or sum
//! of the pieces is within `eps` of the exact hull or sum.

use super::{Aabb, Shape};
use glam::{DAffine3, DVec2, DVec3};

/// The most faces a cylinder's side or a sphere's ring is cut into.
pub const MAX_SEGMENTS: usize = 1024;

/// A flat face: its unit outward normal n, its offset d (n·x = d on it)
/// and its corners, counter-clockwise seen from outside.
#[derive(Clone, Debug)]
pub struct Face {
    pub n: DVec3,
    pub d: f64,
    pub pts: Vec<DVec3>,
}

/// A bounded convex solid, the intersection of its faces' half-spaces.
#[derive(Clone, Debug)]
pub struct Polytope {
    pub faces: Vec<Face>,
    pub bounds: Aabb,
}

impl Polytope {
    fn new(faces: Vec<Face>) -> Option<Polytope> {
        if faces.len() < 4 {
            return None;
        }
        let mut bounds = Aabb::EMPTY;
        for p in faces.iter().flat_map(|f| &f.pts) {
            bounds = bounds.include(*p);
        }
        Some(Polytope { faces, bounds })
    }

    /// The polytope with corners `pts` (placed by `m`) and faces `loops`
    /// of indices, each turned outward by where the corners' centre lies.
    fn from_loops(pts: &[DVec3], loops: &[Vec<usize>], m: &DAffine3) -> Option<Polytope> {
        let w: Vec<DVec3> = pts.iter().map(|&p| m.transform_point3(p)).collect();
        let centre = w.iter().sum::<DVec3>() / w.len() as f64;
        let mut faces = Vec::with_capacity(loops.len());
        for l in loops {
            let mut f: Vec<DVec3> = l.iter().map(|&i| w[i]).collect();
            // Newell's normal: the polygon's area vector.
            let mut n = DVec3::ZERO;
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                n += DVec3::new(
                    (a.y - b.y) * (a.z + b.z),
                    (a.z - b.z) * (a.x + b.x),
                    (a.x - b.x) * (a.y + b.y),
                );
            }
            let Some(mut n) = n.try_normalize() else {
                continue;
            };
            let mid = f.iter().sum::<DVec3>() / f.len() as f64;
            if n.dot(centre - mid) > 0.0 {
                n = -n;
                f.reverse();
            }
            faces.push(Face {
                n,
                d: n.dot(mid),
                pts: f,
            });
        }
        Polytope::new(faces)
    }

    /// The hull of `pts`, `None` when it has no volume (see
    /// [`super::quickhull::hull`]).
    pub fn hull(pts: &[DVec3], tol: f64) -> Option<Polytope> {
        let (v, tris) = super::quickhull::hull(pts, tol)?;
        let loops: Vec<Vec<usize>> = tris
            .iter()
            .map(|t| t.iter().map(|&i| i as usize).collect())
            .collect();
        Polytope::from_loops(&v, &loops, &DAffine3::IDENTITY)
    }

    /// Its corners, each once.
    pub fn vertices(&self) -> Vec<DVec3> {
        let mut v: Vec<DVec3> = self.faces.iter().flat_map(|f| f.pts.clone()).collect();
        v.sort_by(|a, b| {
            a.to_array()
                .partial_cmp(&b.to_array())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        v.dedup();
        v
    }

    /// The least and largest n·x − d over its corners, each 0 within
    /// `tol`.
    fn range(&self, n: DVec3, d: f64, tol: f64) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in self.faces.iter().flat_map(|f| &f.pts) {
            let s = side(n, d, tol, *p);
            lo = lo.min(s);
            hi = hi.max(s);
        }
        (lo, hi)
    }

    /// The part with n·x ≤ d: itself when it lies there (within `tol`),
    /// `None` when nothing of it does.
    pub fn clip(&self, n: DVec3, d: f64, tol: f64) -> Option<Polytope> {
        match self.range(n, d, tol) {
            (_, hi) if hi <= 0.0 => Some(self.clone()),
            (lo, _) if lo >= 0.0 => None,
            _ => self.cut(n, d, tol),
        }
    }

    /// The part with n·x ≤ d, for a plane that has corners on both sides.
    fn cut(&self, n: DVec3, d: f64, tol: f64) -> Option<Polytope> {
        let side = |p: DVec3| side(n, d, tol, p);
        let mut faces = Vec::with_capacity(self.faces.len() + 1);
        let mut cut: Vec<DVec3> = Vec::new();
        for f in &self.faces {
            let mut out: Vec<DVec3> = Vec::with_capacity(f.pts.len() + 2);
            let k = f.pts.len();
            for i in 0..k {
                let (p, q) = (f.pts[i], f.pts[(i + 1) % k]);
                let (sp, sq) = (side(p), side(q));
                if sp <= 0.0 {
                    out.push(p);
                    if sp == 0.0 {
                        cut.push(p);
                    }
                }
                if (sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0) {
                    let x = p + (q - p) * (sp / (sp - sq));
                    out.push(x);
                    cut.push(x);
                }
            }
            out.dedup();
            while out.len() > 1 && out.first() == out.last() {
                out.pop();
            }
            if out.len() >= 3 {
                faces.push(Face {
                    n: f.n,
                    d: f.d,
                    pts: out,
                });
            }
        }
        // The new face: the hull of the points on the plane.
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let flat: Vec<DVec2> = cut
            .iter()
            .map(|&p| DVec2::new(p.dot(u), p.dot(v)))
            .collect();
        let ring = crate::plane::hull::hull_indices_2d(&flat, tol);
        if ring.len() >= 3 {
            faces.push(Face {
                n,
                d,
                pts: ring.iter().map(|&i| cut[i]).collect(),
            });
        }
        Polytope::new(faces)
    }

    /// The part inside `other` too.
    pub fn meet(&self, other: &Polytope, tol: f64) -> Option<Polytope> {
        if !self.overlaps(other, tol) {
            return None;
        }
        let mut rest = self.clone();
        for f in &other.faces {
            rest = rest.clip(f.n, f.d, tol)?;
        }
        Some(rest)
    }

    /// The part outside `other`, as disjoint convex pieces: beyond each of
    /// its faces and within the ones before.
    pub fn minus(&self, other: &Polytope, tol: f64) -> Vec<Polytope> {
        let mut out = Vec::new();
        if !self.overlaps(other, tol) {
            out.push(self.clone());
            return out;
        }
        // Only the faces whose planes cut it: beyond one of them all, it is
        // untouched; within the others, so is every part of it.
        let mut cutting = Vec::new();
        for f in &other.faces {
            let (lo, hi) = self.range(f.n, f.d, tol);
            if lo >= 0.0 {
                out.push(self.clone());
                return out;
            }
            if hi > 0.0 {
                cutting.push(f);
            }
        }
        let mut rest = self.clone();
        for f in cutting {
            match rest.range(f.n, f.d, tol) {
                (_, hi) if hi <= 0.0 => continue,
                (lo, _) if lo >= 0.0 => {
                    out.push(rest);
                    return out;
                }
                _ => {}
            }
            out.extend(rest.cut(-f.n, -f.d, tol));
            match rest.cut(f.n, f.d, tol) {
                Some(r) => rest = r,
                None => return out,
            }
        }
        out
    }

    /// Whether the boxes meet (by more than `tol`).
    pub fn overlaps(&self, other: &Polytope, tol: f64) -> bool {
        (0..3).all(|i| {
            self.bounds.min[i] < other.bounds.max[i] - tol
                && other.bounds.min[i] < self.bounds.max[i] - tol
        })
    }

    /// The shadows of its corners on z = 0 (their hull is its shadow).
    pub fn shadow_z(&self) -> Vec<DVec2> {
        self.faces
            .iter()
            .flat_map(|f| f.pts.iter().map(|p| p.truncate()))
            .collect()
    }

    /// Where its edges meet z = 0, and its corners on it (their hull is
    /// its section by the plane).
    pub fn slice_z0(&self) -> Vec<DVec2> {
        self.slice(|p| p.z)
            .into_iter()
            .map(|p| p.truncate())
            .collect()
    }

    /// Where its edges meet the level set `level = 0` of an affine
    /// function, and its corners on it (their hull is its section there).
    pub fn slice(&self, level: impl Fn(DVec3) -> f64) -> Vec<DVec3> {
        let mut out = Vec::new();
        for f in &self.faces {
            for (i, &a) in f.pts.iter().enumerate() {
                let b = f.pts[(i + 1) % f.pts.len()];
                let (la, lb) = (level(a), level(b));
                if la == 0.0 {
                    out.push(a);
                } else if (la < 0.0) != (lb < 0.0) && lb != 0.0 {
                    out.push(a + (b - a) * (la / (la - lb)));
                }
            }
        }
        out
    }

    /// Its volume, by the divergence theorem over its faces' fans.
    pub fn volume(&self) -> f64 {
        let mut v = 0.0;
        for f in &self.faces {
            for i in 1..f.pts.len() - 1 {
                v += f.pts[0].dot(f.pts[i].cross(f.pts[i + 1]));
            }
        }
        v / 6.0
    }

    /// Its faces as triangles over its corners (fans), for a mesh.
    pub fn triangles(&self) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let (mut v, mut t) = (Vec::new(), Vec::new());
        for f in &self.faces {
            let base = v.len() as u32;
            v.extend(f.pts.iter().copied());
            for i in 1..f.pts.len() as u32 - 1 {
                t.push([base, base + i, base + i + 1]);
            }
        }
        (v, t)
    }
}

/// n·p − d, 0 within `tol`.
pub(super) fn side(n: DVec3, d: f64, tol: f64, p: DVec3) -> f64 {
    let s = n.dot(p) - d;
    if s.abs() <= tol {
        0.0
    } else {
        s
    }
}

/// The thickness of a plane when cutting or hulling what lies in box `b`:
/// 10⁻¹⁰ of its size plus its distance from the origin.
pub fn plane_tolerance(b: &Aabb) -> f64 {
    let far = b.min.abs().max(b.max.abs()).max_element();
    1e-10 * ((b.max - b.min).max_element() + far)
}

/// The thickness of a plane among points `pts`: [`plane_tolerance`] of
/// their box, as for every hull of corners.
pub fn points_tolerance(pts: &[DVec3]) -> f64 {
    let b = pts.iter().fold(Aabb::EMPTY, |b, p| b.include(*p));
    plane_tolerance(&b)
}

/// The convex hull of `pts` as a closed mesh (planes 10⁻¹⁰ of the points'
/// size and distance from the origin thick); `None` when it has no volume.
pub fn hull_mesh(pts: &[DVec3]) -> Option<super::Mesh> {
    let (v, t) = super::quickhull::hull(pts, points_tolerance(pts))?;
    let data = std::sync::Arc::new(super::mesh::MeshData::convex(v, t));
    Some(super::Mesh { data })
}

/// The chords a circle (radius 1, stretched by at most σ) is cut into so
/// that they stray from it by at most `eps`, each spanning `factor` times
/// its share of the turn: n with σ(1 − cos(factor·π/n)) ≤ eps.
fn segments(sigma: f64, eps: f64, factor: f64) -> usize {
    // The fault: a quarter of the chords.
    let coarse = if crate::mutant::active("facets_coarse") {
        0.25
    } else {
        1.0
    };
    let gap = (eps / sigma).min(1.0);
    let step = (1.0 - gap).acos();
    ((coarse * factor * std::f64::consts::PI / step).ceil() as usize).clamp(8, MAX_SEGMENTS)
}

/// The largest stretch of `m` (its largest singular value): the square
/// root of MᵀM's largest eigenvalue, by the closed form for a symmetric
/// 3×3 matrix (Smith, "Eigenvalues of a symmetric 3×3 matrix", 1961),
/// grown by 10⁻⁹ for its rounding; never above the Frobenius norm.
pub fn stretch(m: &DAffine3) -> f64 {
    let c = m.matrix3;
    let g = c.transpose() * c;
    let frobenius = (g.x_axis.x + g.y_axis.y + g.z_axis.z).sqrt();
    let p1 = g.y_axis.x.powi(2) + g.z_axis.x.powi(2) + g.z_axis.y.powi(2);
    let q = (g.x_axis.x + g.y_axis.y + g.z_axis.z) / 3.0;
    let diag = DVec3::new(g.x_axis.x, g.y_axis.y, g.z_axis.z);
    let p2 = (diag - DVec3::splat(q)).length_squared() + 2.0 * p1;
    let largest = if p2 <= 0.0 {
        q
    } else {
        let p = (p2 / 6.0).sqrt();
        let b = (g - glam::DMat3::from_diagonal(DVec3::splat(q))) * (1.0 / p);
        let r = (b.determinant() / 2.0).clamp(-1.0, 1.0);
        q + 2.0 * p * (r.acos() / 3.0).cos()
    };
    (largest.max(0.0).sqrt() * (1.0 + 1e-9)).min(frobenius)
}

/// The largest stretch `m` gives a vector of the plane z = 0 (a little
/// over): how far a section's error in that plane moves under it (a
/// prism's height, however long, moves none of it).
fn section_stretch(m: &DAffine3) -> f64 {
    let (a, b) = (m.matrix3.x_axis, m.matrix3.y_axis);
    let gram = glam::DMat2::from_cols(
        DVec2::new(a.dot(a), a.dot(b)),
        DVec2::new(a.dot(b), b.dot(b)),
    );
    crate::plane::flat::gram_stretch(gram) * (1.0 + 1e-9)
}

/// Leaf `shape` placed by `m` as convex polytopes within `eps` of it
/// (absolute planes' thickness `tol`; none for a flat one); or why not:
/// an unbounded solid, or one past a limit ([`MAX_MESH_CELLS`],
/// [`MAX_TWIST_POINTS`], [`MAX_SUM_CORNERS`]).
///
/// [`MAX_MESH_CELLS`]: super::mesh_cells::MAX_MESH_CELLS
pub fn pieces_of(shape: &Shape, m: &DAffine3, eps: f64, tol: f64) -> Result<Vec<Polytope>, String> {
    pieces_across(shape, m, eps, tol, None)
}

/// [`pieces_of`], a flat region's pieces (a prism's, an offset prism's)
/// cut between levels across world direction `across` where one is given
/// and the region's plane is not level across it ([`trapezoids`]), rather
/// than into triangles.
///
/// [`trapezoids`]: super::trapezoids::trapezoids
pub fn pieces_across(
    shape: &Shape,
    m: &DAffine3,
    eps: f64,
    tol: f64,
    across: Option<DVec3>,
) -> Result<Vec<Polytope>, String> {
    // The rising direction of `across` in the section's plane.
    let up = across.map(|w| DVec2::new(m.matrix3.x_axis.dot(w), m.matrix3.y_axis.dot(w)));
    match shape {
        Shape::Cuboid(c) => {
            let lo = super::cuboid::low(c.centered);
            let pts: Vec<DVec3> = (0..8)
                .map(|i| {
                    let pick = |b: usize| if i & b != 0 { 1.0 } else { lo };
                    DVec3::new(pick(1), pick(2), pick(4))
                })
                .collect();
            let loops = [
                vec![0, 2, 6, 4],
                vec![1, 5, 7, 3],
                vec![0, 4, 5, 1],
                vec![2, 3, 7, 6],
                vec![0, 1, 3, 2],
                vec![4, 6, 7, 5],
            ];
            Ok(Polytope::from_loops(&pts, &loops, m).into_iter().collect())
        }
        Shape::Cone(c) => {
            // Each height's section is the polygon of its circle (the two
            // caps' corners hulled): the error lies in the section's plane.
            let n = segments(section_stretch(m), eps, 1.0);
            let z0 = super::cone::bottom(c.centered);
            let mut pts = Vec::new();
            let mut loops = Vec::new();
            let ring = |r: f64, z: f64, pts: &mut Vec<DVec3>| -> Vec<usize> {
                if r <= 0.0 {
                    pts.push(DVec3::new(0.0, 0.0, z));
                    return vec![pts.len() - 1; n];
                }
                (0..n)
                    .map(|i| {
                        let a = std::f64::consts::TAU * i as f64 / n as f64;
                        pts.push(DVec3::new(r * a.cos(), r * a.sin(), z));
                        pts.len() - 1
                    })
                    .collect()
            };
            let bottom = ring(c.r0, z0, &mut pts);
            let top = ring(c.r1, z0 + 1.0, &mut pts);
            if c.r0 > 0.0 {
                loops.push(bottom.clone());
            }
            if c.r1 > 0.0 {
                loops.push(top.clone());
            }
            for i in 0..n {
                let j = (i + 1) % n;
                let mut l = vec![bottom[i], bottom[j], top[j], top[i]];
                l.dedup();
                loops.push(l);
            }
            Ok(Polytope::from_loops(&pts, &loops, m).into_iter().collect())
        }
        Shape::Sphere(_) => {
            let n = segments(stretch(m), eps, std::f64::consts::SQRT_2);
            let rings = n.div_ceil(2);
            let mut pts = vec![DVec3::Z, -DVec3::Z];
            for k in 1..rings {
                let th = std::f64::consts::PI * k as f64 / rings as f64;
                for i in 0..n {
                    let a = std::f64::consts::TAU * i as f64 / n as f64;
                    pts.push(DVec3::new(th.sin() * a.cos(), th.sin() * a.sin(), th.cos()));
                }
            }
            let at = |k: usize, i: usize| 2 + (k - 1) * n + i % n;
            let mut loops = Vec::new();
            for i in 0..n {
                loops.push(vec![0, at(1, i), at(1, i + 1)]);
                loops.push(vec![1, at(rings - 1, i + 1), at(rings - 1, i)]);
                for k in 1..rings - 1 {
                    loops.push(vec![at(k, i), at(k + 1, i), at(k + 1, i + 1), at(k, i + 1)]);
                }
            }
            Ok(Polytope::from_loops(&pts, &loops, m).into_iter().collect())
        }
        Shape::Mesh(mesh) => {
            let d = &mesh.data;
            // Not closed: no inside to cut. OpenSCAD's render cannot make
            // it a Nef polyhedron and leaves it out ("The given mesh is
            // not closed!"), so its pieces are none.
            if super::mesh::edge_use(&d.tris).0 > 0 {
                return Ok(Vec::new());
            }
            let w: Vec<DVec3> = d.verts.iter().map(|&p| m.transform_point3(p)).collect();
            let Some(hull) = Polytope::hull(&w, tol) else {
                return Ok(Vec::new());
            };
            // Convex when it fills its hull: the same volume.
            let own = signed_volume(&w, &d.tris).abs();
            let full = hull.volume();
            let size = (hull.bounds.max - hull.bounds.min).max_element();
            // The fault: a mesh taken as its hull, convex or not.
            if (full - own).abs() <= tol * size * size || crate::mutant::active("mesh_hulled") {
                return Ok(vec![hull]);
            }
            // Not convex: its cells, exactly.
            super::mesh_cells::mesh_cells(&w, &d.tris, tol, super::mesh_cells::MAX_MESH_CELLS)
                .ok_or_else(|| {
                    format!(
                        "a mesh that crosses itself or is cut into more than {} convex cells",
                        super::mesh_cells::MAX_MESH_CELLS
                    )
                })
        }
        Shape::Prism(q) => {
            // Curved edges (text, SVG) as chords within eps of them.
            let flat;
            let loops = if q.region.curved() {
                // The section's error, grown by the taper at most.
                let sigma = section_stretch(m) * q.top.abs().max(1.0);
                flat = crate::plane::flat::chords(&q.region.outlines, eps / sigma);
                &flat
            } else {
                &q.region.outlines.loops
            };
            let z = q.z_lo();
            // A convex outline (a circle's chords, a square) is one prism; a
            // piece whose top shrinks to a point is a pyramid.
            let pieces = convex_loops(loops, up);
            let out = pieces
                .into_iter()
                .filter_map(|t| prism(t.into_iter(), m, z, q.top, tol))
                .collect();
            Ok(out)
        }
        Shape::Lathe(l) => {
            let sigma = stretch(m);
            let loops = if l.profile.curved() {
                crate::plane::flat::chords(&l.profile.outlines, 0.5 * eps / sigma)
            } else {
                l.profile.outlines.loops.clone()
            };
            Ok(turned(&loops, m, eps, tol))
        }
        Shape::Torus(t) => {
            // The tube's circle about (1, 0), radius `minor`: its chords
            // within eps/2, the part at x ≥ 0 (a horn or spindle torus
            // turns only that: the apple).
            let sigma = stretch(m);
            let n = segments(sigma * t.minor, 0.5 * eps, 1.0);
            let circle: Vec<DVec2> = (0..n)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / n as f64;
                    DVec2::new(1.0, 0.0) + DVec2::from_angle(a) * t.minor
                })
                .collect();
            let o =
                crate::plane::figure::clip_right(&crate::plane::Outlines::polygons(vec![circle]));
            Ok(turned(&o.loops, m, eps, tol))
        }
        Shape::Ring(r) => {
            // The ellipse (1, 0) + M·u turned: its polygon within eps/2
            // (stretched by the transform too).
            let e = glam::DAffine2::from_mat2_translation(r.m, DVec2::X);
            let Some(l) = crate::plane::flat::ellipse(e, 0.5 * eps / stretch(m)) else {
                return Ok(Vec::new());
            };
            Ok(turned(&[l], m, eps, tol))
        }
        Shape::Twisted(tw) => twisted(tw, m, eps, tol),
        Shape::OffsetPrism(q) => {
            // The offset of the outline's chords, exact, within eps/2 of
            // it (an offset moves no farther than what it offsets), its
            // circles' chords within eps/2 more: the loops of its outline,
            // as a straight prism's.
            use crate::plane::figure::Figure;
            let sigma = section_stretch(m);
            let leaf = Figure::Offset(q.region.clone(), glam::DAffine2::IDENTITY);
            let Some(flat) = crate::plane::flat::flattened(&leaf, eps / sigma, false)? else {
                return Ok(Vec::new());
            };
            let parts = convex_parts(&flat, up).ok_or_else(|| {
                format!(
                    "an offset whose outline csgrt cannot read (more than {} edges)",
                    crate::plane::sites::MAX_PIECES
                )
            })?;
            let z = if q.centered { -0.5 } else { 0.0 };
            let prisms = parts
                .iter()
                .filter_map(|part| prism(part.iter().copied(), m, z, 1.0, tol));
            Ok(prisms.collect())
        }
        // A hull or a sum nested in what is cut: its parts' polytopes
        // hulled, summed corner by corner.
        Shape::Convex(c) => Ok(summed_hulls(&c.hulls, m, eps, tol)?.into_iter().collect()),
        // An exact union of primitives (a rounded box): theirs.
        Shape::Rounded(r) => {
            let mut out = Vec::new();
            for q in &r.pieces {
                out.extend(pieces_across(
                    &q.shape,
                    &(*m * q.xf.to_world),
                    eps,
                    tol,
                    across,
                )?);
            }
            Ok(out)
        }
        // A shadow: the union of its triangles' prisms, z from 0 to 1.
        Shape::Shadow(sh) => {
            let soup = &sh.soup;
            let prisms = soup.tris.iter().filter_map(|t| {
                let corners = t.iter().map(|&i| soup.pts[i as usize]);
                prism(corners, m, 0.0, 1.0, tol)
            });
            Ok(prisms.collect())
        }
        Shape::Halfspace(_) => Err("an unbounded solid (a halfspace)".into()),
    }
}

/// The hull of a convex polygon's corners at height `z` and, scaled by
/// `top`, at `z + 1`, placed by `m` (a prism, or a pyramid where the top
/// shrinks to a point); `None` when it is flat.
fn prism(
    corners: impl Iterator<Item = DVec2>,
    m: &DAffine3,
    z: f64,
    top: f64,
    tol: f64,
) -> Option<Polytope> {
    let pts: Vec<DVec3> = corners
        .flat_map(|v| {
            [
                m.transform_point3(v.extend(z)),
                m.transform_point3((v * top).extend(z + 1.0)),
            ]
        })
        .collect();
    Polytope::hull(&pts, tol)
}

/// The most corner sums a nested Minkowski sum's polytope is hulled from.
pub const MAX_SUM_CORNERS: usize = 2_000_000;

/// The sum of the hulls of `hulls`' parts (placed by `m`) as one polytope
/// within `eps`: each part's polytopes within eps/k (k hulls summed: a
/// hull moves no more than its parts, a sum by the sum of its operands'),
/// their corners hulled, each hull's corners added to every corner of the
/// sum so far and hulled again (`None` when the sum is flat); or why a
/// part cannot be cut, or that the sum needs more than
/// [`MAX_SUM_CORNERS`] corner sums.
fn summed_hulls(
    hulls: &[Vec<super::convex::ConvexPart>],
    m: &DAffine3,
    eps: f64,
    tol: f64,
) -> Result<Option<Polytope>, String> {
    let e = eps / hulls.len().max(1) as f64;
    let sum = corner_sum(
        hulls,
        |h| {
            let mut pts = Vec::new();
            for part in h {
                for p in pieces_of(&part.shape, &(*m * part.to_world), e, tol)? {
                    pts.extend(p.vertices());
                }
            }
            Ok(pts)
        },
        |pts| Polytope::hull(pts, tol).map(|p| p.vertices()),
        || format!("a nested sum of more than {MAX_SUM_CORNERS} corner sums"),
    )?;
    Ok(Polytope::hull(&sum, tol))
}

/// The corners of the Minkowski sum of the hulls of `hulls`' point sets
/// (`corners` of each, or its error): each set's hull's corners (`hull`,
/// `None` for a flat set, whose points all serve) added to every corner
/// of the sum so far and hulled again; `too_many` where that would take
/// more than [`MAX_SUM_CORNERS`] corner sums.
pub fn corner_sum<'a, T, E>(
    hulls: &'a [T],
    mut corners: impl FnMut(&'a T) -> Result<Vec<DVec3>, E>,
    hull: impl Fn(&[DVec3]) -> Option<Vec<DVec3>>,
    too_many: impl FnOnce() -> E,
) -> Result<Vec<DVec3>, E> {
    let mut sum = vec![DVec3::ZERO];
    for h in hulls {
        let pts = corners(h)?;
        let own = hull(&pts).unwrap_or(pts);
        if sum.len() * own.len() > MAX_SUM_CORNERS {
            return Err(too_many());
        }
        let all: Vec<DVec3> = sum
            .iter()
            .flat_map(|&a| own.iter().map(move |&b| a + b))
            .collect();
        sum = hull(&all).unwrap_or(all);
    }
    Ok(sum)
}

/// Convex polygons whose union is a straight figure: a convex loop
/// itself, other polygons' triangles, a union's parts' parts, another
/// combination's outline's triangles; `None` when that outline cannot be
/// read.
fn convex_parts(f: &crate::plane::figure::Figure, up: Option<DVec2>) -> Option<Vec<Vec<DVec2>>> {
    use crate::plane::figure::Figure;
    let loops = match f {
        Figure::Op(crate::math::boolean::Op::Union, kids) => {
            let mut out = Vec::new();
            for k in kids {
                out.extend(convex_parts(k, up)?);
            }
            return Some(out);
        }
        Figure::Polygon(o) if !o.curved() => o.loops.clone(),
        Figure::Op(..) => crate::plane::sites::outline(f)?.loops,
        _ => return None,
    };
    Some(convex_loops(&loops, up))
}

/// The most corners a twisted prism's convex pieces may have in all
/// (slabs times its section's pieces' corners): the slabs are thin (their
/// count grows with the twist times a piece's width over eps), and past
/// this the cut and hull take minutes.
pub const MAX_TWIST_POINTS: usize = 200_000;

/// A twisted or unevenly scaled prism placed by `m` as convex polytopes
/// within eps of it: its section's convex pieces (an ellipse's polygon
/// within eps/2) at the bottom and top of n slabs, each piece's two copies
/// hulled. Between heights z₀ and z₁ a section point p sweeps M(z)·p, M(z)
/// = S(z)·R(−θz); the hull's section at (1 − u)z₀ + u·z₁ is the Minkowski
/// combination (1 − u)M₀P + uM₁P, which holds M_u·P up to the curve's
/// bulge ρ|M″|Δz²/8 and exceeds it by at most u(1 − u)|M₁ − M₀|·D ≤
/// D·|M′|Δz/4 (D a piece's diameter, ρ its reach from the axis). With
/// |M′| ≤ |s − 1| + s·|θ| and |M″| ≤ 2|s − 1||θ| + s·θ² (s the larger
/// scale), n makes each term at most eps/4, stretched by σ, m's largest
/// stretch in the section's plane (where those errors lie; its height is
/// mapped linearly, exactly).
fn twisted(tw: &super::Twisted, m: &DAffine3, eps: f64, tol: f64) -> Result<Vec<Polytope>, String> {
    // The errors above lie in the section's plane: m's stretch there.
    let sigma = section_stretch(m);
    let big = tw.scale.max_element().max(1.0);
    let loops = match &tw.section {
        super::twist::TwistSection::Region(r) if !r.curved() => r.outlines.loops.clone(),
        // Curved edges (text, SVG) as chords within eps/2 of them, as an
        // ellipse's polygon.
        super::twist::TwistSection::Region(r) => {
            crate::plane::flat::chords(&r.outlines, 0.5 * eps / (sigma * big))
        }
        super::twist::TwistSection::Ellipse(e) => {
            match crate::plane::flat::ellipse(*e, 0.5 * eps / (sigma * big)) {
                Some(l) => vec![l],
                None => return Ok(Vec::new()),
            }
        }
    };
    let pieces = convex_loops(&loops, None);
    let diameter = pieces
        .iter()
        .map(|p| {
            let (lo, hi) = p
                .iter()
                .fold((p[0], p[0]), |(a, b), &q| (a.min(q), b.max(q)));
            (hi - lo).length()
        })
        .fold(0.0f64, f64::max);
    let reach = loops
        .iter()
        .flatten()
        .fold(0.0f64, |r, p| r.max(p.length()));
    let theta = tw.twist.abs();
    let ds = (tw.scale - DVec2::ONE).abs().max_element();
    let first = sigma * diameter * (ds + big * theta) / 4.0;
    let second = sigma * reach * (2.0 * ds * theta + big * theta * theta) / 8.0;
    let quarter = 0.25 * eps;
    let n = (first / quarter)
        .ceil()
        .max((second / quarter).sqrt().ceil())
        .max(1.0);
    let corners: usize = pieces.iter().map(Vec::len).sum();
    if !n.is_finite() || n * corners as f64 > MAX_TWIST_POINTS as f64 {
        return Err(format!(
            "a twist whose slabs within {eps:.1e} have more than {MAX_TWIST_POINTS} corners"
        ));
    }
    let n = n as usize;
    let z0 = super::cone::bottom(tw.centered);
    let at = |p: DVec2, z: f64| {
        let s = DVec2::ONE + (tw.scale - DVec2::ONE) * z;
        // The fault: the slabs turned the other way.
        let turn = if crate::mutant::active("twist_pieces_reversed") {
            tw.twist
        } else {
            -tw.twist
        };
        let q = glam::DMat2::from_angle(turn * z) * p * s;
        m.transform_point3(q.extend(z0 + z))
    };
    let mut out = Vec::with_capacity(n * pieces.len());
    for k in 0..n {
        let (a, b) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
        for piece in &pieces {
            let pts: Vec<DVec3> = piece.iter().flat_map(|&p| [at(p, a), at(p, b)]).collect();
            out.extend(Polytope::hull(&pts, tol));
        }
    }
    Ok(out)
}

/// A region's loops as convex polygons covering it: the loop itself when
/// it is one convex loop, else its trapezoids between levels across `up`
/// where that is given and nonzero and the loops do not cross, else its
/// triangles.
fn convex_loops(loops: &[Vec<DVec2>], up: Option<DVec2>) -> Vec<Vec<DVec2>> {
    if let [l] = loops {
        if crate::plane::hull::convex_polygon(l) {
            return vec![l.clone()];
        }
    }
    if let Some(up) = up.filter(|u| *u != DVec2::ZERO) {
        if let Some(pieces) = super::trapezoids::trapezoids(loops, up) {
            return pieces;
        }
    }
    super::triangulate::cap(loops)
        .into_iter()
        .map(|t| t.iter().map(|&(l, i)| loops[l][i]).collect())
        .collect()
}

/// The box from `lo` to `hi` as a polytope.
pub(super) fn box_polytope(lo: DVec3, hi: DVec3, tol: f64) -> Option<Polytope> {
    let corners: Vec<DVec3> = (0..8)
        .map(|i| {
            let pick = |k: usize, a: f64, z: f64| if i & k != 0 { z } else { a };
            DVec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            )
        })
        .collect();
    Polytope::hull(&corners, tol)
}

/// The signed volume of triangles `tris` on corners `w` (positive when
/// they are turned outward).
pub(super) fn signed_volume(w: &[DVec3], tris: &[[u32; 3]]) -> f64 {
    tris.iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| w[i as usize]);
            a.dot(b.cross(c))
        })
        .sum::<f64>()
        / 6.0
}

/// The part in box `b` (grown by `tol`) of the halfspace z ≤ 0 placed by
/// `m`: the box's polytope clipped by the plane; `None` when nothing of
/// the box is in it, or `m` flattens it.
pub fn halfspace_in(m: &DAffine3, b: &Aabb, tol: f64) -> Option<Polytope> {
    if b.is_empty() || !b.is_bounded() {
        return None;
    }
    let boxed = box_polytope(b.min - DVec3::splat(tol), b.max + DVec3::splat(tol), tol)?;
    // The plane z = 0 placed: normal M⁻ᵀ·z, through m's origin.
    let n = m.matrix3.inverse().transpose() * DVec3::Z;
    let n = n.try_normalize()?;
    boxed.clip(n, n.dot(m.translation), tol)
}

/// The turn about the z axis of a profile (x the distance from the axis,
/// y along z; within eps/2 of the exact one), placed by `m`, as convex
/// polytopes within eps of it: n wedges with σ·ρ(1 − cos(π/n)) ≤ eps/2 (ρ
/// the profile's reach), each convex piece of the profile (the profile
/// itself when it is one convex loop, else its triangles) the hull of its
/// two copies at the wedge's sides. A point of P × [θ₀, θ₁] (cylindrical)
/// lies within ρ(1 − cos(Δ/2)) of the chord between its two copies, and a
/// point of that hull, a convex combination of points in the wedge, lies
/// within as much of P × [θ₀, θ₁] (its radius is between cos(Δ/2) and 1
/// times the combination of theirs).
fn turned(loops: &[Vec<DVec2>], m: &DAffine3, eps: f64, tol: f64) -> Vec<Polytope> {
    let reach = loops.iter().flatten().fold(0.0f64, |r, p| r.max(p.x.abs()));
    if reach == 0.0 || loops.is_empty() {
        return Vec::new();
    }
    let n = segments(stretch(m) * reach, 0.5 * eps, 1.0);
    // The fault: a quarter of the wedges.
    let n = if crate::mutant::active("turn_wedges_coarse") {
        (n / 4).max(3)
    } else {
        n
    };
    let pieces = convex_loops(loops, None);
    let at = |p: DVec2, a: f64| m.transform_point3(DVec3::new(p.x * a.cos(), p.x * a.sin(), p.y));
    let mut out = Vec::with_capacity(n * pieces.len());
    for k in 0..n {
        let (a0, a1) = (
            std::f64::consts::TAU * k as f64 / n as f64,
            std::f64::consts::TAU * (k + 1) as f64 / n as f64,
        );
        for piece in &pieces {
            let pts: Vec<DVec3> = piece.iter().flat_map(|&p| [at(p, a0), at(p, a1)]).collect();
            out.extend(Polytope::hull(&pts, tol));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(lo: DVec3, hi: DVec3) -> Polytope {
        let m = DAffine3::from_scale_rotation_translation(hi - lo, glam::DQuat::IDENTITY, lo);
        pieces_of(
            &Shape::Cuboid(super::super::Cuboid { centered: false }),
            &m,
            1e-3,
            1e-12,
        )
        .unwrap()
        .remove(0)
    }

    #[test]
    fn the_stretch_is_the_largest_singular_value() {
        let r = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0);
        let m = DAffine3::from_scale_rotation_translation(DVec3::new(2.0, 7.0, 3.0), r, DVec3::ONE);
        assert!((stretch(&m) - 7.0).abs() < 1e-7);
        assert!((stretch(&DAffine3::IDENTITY) - 1.0).abs() < 1e-8);
        let shear = DAffine3::from_cols_array(&[
            1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
        ]);
        // [[1,1],[0,1]]: singular values of the golden ratio.
        assert!((stretch(&shear) - (1.0 + 5f64.sqrt()) / 2.0).abs() < 1e-8);
    }

    #[test]
    fn a_hull_meshs_support_climbs_to_the_farthest_corner() {
        let ball = pieces_of(
            &Shape::Sphere(super::super::Sphere),
            &DAffine3::from_scale(DVec3::new(3.0, 1.0, 2.0)),
            1e-3,
            1e-12,
        )
        .unwrap();
        let mesh = hull_mesh(&ball[0].vertices()).unwrap();
        let mut seed = 11u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..500 {
            let d = DVec3::new(next(), next(), next());
            let climbed = mesh.data.farthest(d).unwrap().dot(d);
            let scanned = mesh
                .data
                .verts
                .iter()
                .map(|v| v.dot(d))
                .fold(f64::MIN, f64::max);
            assert!(climbed >= scanned - 1e-12, "{climbed} {scanned}");
        }
    }

    #[test]
    fn a_turned_circle_is_within_eps_of_the_torus_volume() {
        // Pappus: the torus of radii R and r holds 2π²Rr²; pieces within
        // eps of its surface (area 4π²Rr) change that by at most area·eps,
        // and lie inside it (chords of the tube, chords of the turn).
        let (big, small) = (10.0f64, 2.0f64);
        let m = DAffine3::from_scale(DVec3::splat(big));
        let torus = Shape::Torus(super::super::Torus { minor: small / big });
        let pi = std::f64::consts::PI;
        let exact = 2.0 * pi * pi * big * small * small;
        let area = 4.0 * pi * pi * big * small;
        for eps in [1e-1, 1e-3] {
            let v: f64 = pieces_of(&torus, &m, eps, 1e-12)
                .unwrap()
                .iter()
                .map(Polytope::volume)
                .sum();
            assert!(v < exact && v > exact - area * eps, "{eps}: {v} {exact}");
        }
        // A turned square profile: a washer, π(R₂² − R₁²)·h.
        let square = crate::plane::Outlines::polygons(vec![vec![
            DVec2::new(3.0, 0.0),
            DVec2::new(5.0, 0.0),
            DVec2::new(5.0, 2.0),
            DVec2::new(3.0, 2.0),
        ]]);
        let lathe = Shape::Lathe(super::super::Lathe::new(std::sync::Arc::new(
            crate::plane::Region::new(square),
        )));
        let v: f64 = pieces_of(&lathe, &DAffine3::IDENTITY, 1e-3, 1e-12)
            .unwrap()
            .iter()
            .map(Polytope::volume)
            .sum();
        let washer = pi * (25.0 - 9.0) * 2.0;
        assert!(
            v < washer && v > washer - 2.0 * pi * (5.0 + 3.0 + 16.0) * 1e-3,
            "{v}"
        );
    }

    #[test]
    fn a_twisted_square_keeps_its_volume_within_eps() {
        // A 4×4 square about the axis twisted by 90° over a height of 10:
        // every section is the square turned, so the volume is 160; the
        // slabs' hulls lie within eps of the twisted sides (area ≤ the
        // perimeter times the helix's length), so they hold 160 within that
        // area times eps. Scaled unevenly (1 to 2 in x), the sections' area
        // grows as 16·(1 + z): 16·10·1.5 = 240.
        let square = crate::plane::Outlines::polygons(vec![vec![
            DVec2::new(-2.0, -2.0),
            DVec2::new(2.0, -2.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(-2.0, 2.0),
        ]]);
        let region = std::sync::Arc::new(crate::plane::Region::new(square));
        let m = DAffine3::from_scale(DVec3::new(1.0, 1.0, 10.0));
        for (scale, exact) in [(DVec2::ONE, 160.0), (DVec2::new(2.0, 1.0), 240.0)] {
            let tw = Shape::Twisted(super::super::Twisted {
                section: super::super::twist::TwistSection::Region(region.clone()),
                twist: std::f64::consts::FRAC_PI_2,
                scale,
                centered: false,
            });
            for eps in [1e-1, 1e-2] {
                let p = pieces_of(&tw, &m, eps, 1e-12).unwrap();
                let v: f64 = p.iter().map(Polytope::volume).sum();
                let side = 2.0 * (4.0 * scale.x + 4.0) * 10.0 * 1.5;
                assert!((v - exact).abs() <= side * eps, "{eps}: {v} {exact}");
            }
        }
    }

    #[test]
    fn a_halfspace_in_a_box_is_the_box_cut_by_its_plane() {
        // z ≤ 0 turned to x + y ≤ 0 (normal (1, 1, 0)/√2) in the box
        // [−1, 1]³: half the box.
        let m = DAffine3::from_mat3(glam::DMat3::from_cols(
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(-1.0, 1.0, 0.0).normalize(),
            DVec3::new(1.0, 1.0, 0.0).normalize(),
        ));
        let b = Aabb {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        let half = halfspace_in(&m, &b, 0.0).unwrap();
        assert!((half.volume() - 4.0).abs() < 1e-12, "{}", half.volume());
        // Moved off the box: nothing.
        let away = DAffine3::from_translation(DVec3::new(0.0, 0.0, -5.0));
        assert!(halfspace_in(&away, &b, 0.0).is_none());
    }

    #[test]
    fn a_cube_minus_a_cube_through_it_is_four_pieces_of_the_right_volume() {
        let plate = cube(DVec3::ZERO, DVec3::new(10.0, 10.0, 2.0));
        let hole = cube(DVec3::new(3.0, 4.0, -1.0), DVec3::new(6.0, 8.0, 3.0));
        let parts = plate.minus(&hole, 1e-12);
        let total: f64 = parts.iter().map(Polytope::volume).sum();
        assert!((total - (200.0 - 24.0)).abs() < 1e-9, "{total}");
        assert_eq!(parts.len(), 4);
        let both = plate.meet(&hole, 1e-12).unwrap();
        assert!((both.volume() - 24.0).abs() < 1e-9);
        // Apart: nothing met, nothing taken.
        let far = cube(DVec3::splat(20.0), DVec3::splat(21.0));
        assert!(plate.meet(&far, 1e-12).is_none());
        assert_eq!(plate.minus(&far, 1e-12).len(), 1);
    }

    #[test]
    fn a_sphere_and_a_cylinder_stay_within_eps_of_the_surface() {
        let m = DAffine3::from_scale(DVec3::splat(5.0));
        for eps in [1e-1, 1e-3] {
            let ball = pieces_of(&Shape::Sphere(super::super::Sphere), &m, eps, 1e-12).unwrap();
            for f in &ball[0].faces {
                let mid = f.pts.iter().sum::<DVec3>() / f.pts.len() as f64;
                // The face's plane is within eps of the sphere: its
                // distance from the centre at least 5 − eps.
                assert!(f.d >= 5.0 - eps, "{} {}", f.d, eps);
                assert!(mid.length() <= 5.0 + 1e-9);
            }
            let v = ball[0].volume();
            let exact = 4.0 / 3.0 * std::f64::consts::PI * 125.0;
            assert!(v < exact && v > exact - 4.0 * std::f64::consts::PI * 25.0 * eps);
            let cone = super::super::Cone {
                r0: 1.0,
                r1: 1.0,
                centered: true,
            };
            let cyl = pieces_of(&Shape::Cone(cone), &m, eps, 1e-12).unwrap();
            for f in &cyl[0].faces {
                assert!(f.d >= 2.5 - 1e-9 || f.d >= 5.0 - eps, "{}", f.d);
            }
        }
    }
}
