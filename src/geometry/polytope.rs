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
        let mut out = Vec::new();
        for f in &self.faces {
            for (i, &a) in f.pts.iter().enumerate() {
                let b = f.pts[(i + 1) % f.pts.len()];
                if a.z == 0.0 {
                    out.push(a.truncate());
                } else if (a.z < 0.0) != (b.z < 0.0) && b.z != 0.0 {
                    let u = a.z / (a.z - b.z);
                    out.push((a + (b - a) * u).truncate());
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
fn side(n: DVec3, d: f64, tol: f64, p: DVec3) -> f64 {
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

/// The convex hull of `pts` as a closed mesh (planes 10⁻¹⁰ of the points'
/// size and distance from the origin thick); `None` when it has no volume.
pub fn hull_mesh(pts: &[DVec3]) -> Option<super::Mesh> {
    let b = pts.iter().fold(Aabb::EMPTY, |b, p| b.include(*p));
    let (v, t) = super::quickhull::hull(pts, plane_tolerance(&b))?;
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

/// Leaf `shape` placed by `m` as convex polytopes within `eps` of it
/// (absolute planes' thickness `tol`); `None` for a solid this cannot cut
/// into polytopes (curved outlines, turns, tori, twists, non-convex
/// meshes, unbounded solids).
pub fn pieces_of(shape: &Shape, m: &DAffine3, eps: f64, tol: f64) -> Option<Vec<Polytope>> {
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
            Polytope::from_loops(&pts, &loops, m).map(|p| vec![p])
        }
        Shape::Cone(c) => {
            let n = segments(stretch(m), eps, 1.0);
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
            Polytope::from_loops(&pts, &loops, m).map(|p| vec![p])
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
            Polytope::from_loops(&pts, &loops, m).map(|p| vec![p])
        }
        Shape::Mesh(mesh) => {
            let d = &mesh.data;
            let w: Vec<DVec3> = d.verts.iter().map(|&p| m.transform_point3(p)).collect();
            let hull = Polytope::hull(&w, tol)?;
            // Convex when it fills its hull: the same volume.
            let own = d
                .tris
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| w[i as usize]);
                    a.dot(b.cross(c))
                })
                .sum::<f64>()
                .abs()
                / 6.0;
            let full = hull.volume();
            let size = (hull.bounds.max - hull.bounds.min).max_element();
            ((full - own).abs() <= tol * size * size).then(|| vec![hull])
        }
        Shape::Prism(q) => {
            // Curved edges (text, SVG) as chords within eps of them.
            let flat;
            let loops = if q.region.curved() {
                let sigma = stretch(m) * q.top.abs().max(1.0);
                flat = crate::plane::flat::chords(&q.region.outlines, eps / sigma);
                &flat
            } else {
                &q.region.outlines.loops
            };
            let z = q.z_lo();
            let mut out = Vec::new();
            // A convex outline (a circle's chords, a square) is one prism.
            if let [l] = &loops[..] {
                if crate::plane::hull::convex_polygon(l) {
                    let pts: Vec<DVec3> = l
                        .iter()
                        .flat_map(|&v| {
                            [
                                m.transform_point3(v.extend(z)),
                                m.transform_point3((v * q.top).extend(z + 1.0)),
                            ]
                        })
                        .collect();
                    return Some(Polytope::hull(&pts, tol).into_iter().collect());
                }
            }
            for t in super::triangulate::cap(loops) {
                let mut pts = Vec::with_capacity(6);
                for (l, i) in t {
                    let v = loops[l][i];
                    pts.push(m.transform_point3(v.extend(z)));
                    pts.push(m.transform_point3((v * q.top).extend(z + 1.0)));
                }
                // A triangle whose top shrinks to a point is a pyramid.
                if let Some(p) = Polytope::hull(&pts, tol) {
                    out.push(p);
                }
            }
            Some(out)
        }
        _ => None,
    }
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
