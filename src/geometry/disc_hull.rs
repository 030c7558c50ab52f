//! The hull of parallel discs of any radii — of cylinders and cones whose
//! axes are parallel and whose sections are one disc scaled (a rounded
//! plate under a smaller rounded top, a chamfered boss, a stand of cones)
//! — and of such discs with points (polytopes' corners: a disc of radius
//! zero), written out as exact primitives.
//!
//! In the frame where the discs are circles in planes z = const, give each
//! disc its centre c and radius ρ, a point (c, ρ) of four dimensions; the
//! hull of the discs is {q + q_ρ·d : q in H, |d| ≤ 1, d horizontal}, H the
//! four-dimensional hull of those points (a point of the hull of discs is
//! Σλᵢ(cᵢ + ρᵢdᵢ), and Σλᵢρᵢdᵢ is (Σλᵢρᵢ)·d for some such d). Its section
//! at a height is the section of H there, a set of discs, and the hull of
//! finitely many discs is the hull of their centres, the discs on its
//! boundary, and between two neighbours there the trapezoid from their
//! centres out along the normal m of the segment that touches both. So the
//! hull is the union of:
//!
//! * the hull of the centres;
//! * for each pair of discs at different heights that is an edge of H on
//!   the boundary — some direction (u, w), u a unit horizontal vector, has
//!   both discs farthest along it, over an open set of u — the frustum
//!   swept between them (its sections discs), a cone sheared to its axis;
//! * for each plane that touches three discs with every disc on one side
//!   (a face of H whose discs appear on the boundary: along the discs
//!   between two neighbours of a section, the touching segment's normal m
//!   is the same at every height), the hull of those discs' centres c and
//!   of c + ρ·u, u the plane's normal made horizontal.
//!
//! A hull whose discs all have one radius is `disc_sum`'s (one closed mesh
//! rather than a piece a face).

use glam::{DAffine3, DMat3, DVec3};

use crate::geometry::ball_sum::Pieces;
use crate::geometry::convex::ConvexPart;
use crate::geometry::disc_sum::{in_frustum, minkowski, scale, shape_of, vertices};
use crate::geometry::{Cone, Shape};
use crate::plane::hull::MAX_HULL_POINTS;

/// A disc: its centre in the discs' frame and its radius there.
type Disc = (DVec3, f64);

/// The discs at the two ends of a cone part: world centres and the
/// discs' shape matrices Σ aᵢaᵢᵀ over their half-axes (zero for an apex).
fn ends(p: &ConvexPart) -> Option<[(DVec3, DMat3, [DVec3; 2]); 2]> {
    let Shape::Cone(c) = &p.shape else {
        return None;
    };
    let m = &p.to_world;
    let z0 = super::cone::bottom(c.centered);
    let end = |z: f64, r: f64| {
        let axes = [m.matrix3.x_axis * r, m.matrix3.y_axis * r];
        (m.transform_point3(DVec3::Z * z), shape_of(&axes), axes)
    };
    Some([end(z0, c.r0), end(z0 + 1.0, c.r1)])
}

fn trace(m: &DMat3) -> f64 {
    m.x_axis.x + m.y_axis.y + m.z_axis.z
}

/// The pieces of the hull (in the parts' frame) when `hulls` is one hull of
/// cylinders and cones whose discs are one disc scaled, in parallel planes
/// (10⁻¹² of its size), plus polytopes — a corner inside the hull of those
/// parts' own discs' centres or inside one of the parts (10⁻⁹ of the set's
/// size) left out, any other a disc of radius zero (a boss hulled with a
/// plate) —, or such a hull summed with polytopes (the discs moved to every
/// corner of their sum). `None` otherwise, past [`MAX_HULL_POINTS`] discs,
/// or when the hull is flat.
pub fn as_disc_hull(hulls: &[Vec<ConvexPart>]) -> Option<Pieces> {
    let with = hulls
        .iter()
        .position(|h| h.iter().any(|p| ends(p).is_some()))?;
    let cones: Vec<_> = hulls[with].iter().filter_map(ends).collect();
    // The frame: the largest disc's half-axes and their normal.
    let (_, sref, axes) = cones
        .iter()
        .flatten()
        .max_by(|a, b| trace(&a.1).total_cmp(&trace(&b.1)))?;
    let size = trace(sref);
    if size.is_nan() || size <= 0.0 {
        return None;
    }
    let [a1, a2] = *axes;
    let n = a1.cross(a2);
    let l = DMat3::from_cols(a1, a2, n / n.length().sqrt());
    let frame = DAffine3::from_mat3_translation(l, cones[0][0].0);
    let local = frame.inverse();
    if !local.is_finite() {
        return None;
    }
    let mut discs: Vec<Disc> = Vec::new();
    let mut axis_ends: Vec<[Disc; 2]> = Vec::new();
    for c in &cones {
        let mut pair = [(DVec3::ZERO, 0.0); 2];
        for (k, (centre, s, _)) in c.iter().enumerate() {
            let rho2 = trace(s) / size;
            let off = (*s - *sref * rho2).to_cols_array();
            if off.iter().any(|v| v.abs() > 1e-12 * size) {
                return None;
            }
            pair[k] = (local.transform_point3(*centre), rho2.sqrt());
        }
        axis_ends.push(pair);
        discs.extend(pair);
    }
    let mut others = Vec::new();
    let mut corners: Vec<DVec3> = vec![DVec3::ZERO];
    for (k, h) in hulls.iter().enumerate() {
        let mut pts = Vec::new();
        for p in h {
            if ends(p).is_some() {
                if k != with {
                    return None;
                }
                continue;
            }
            pts.extend(p.corners()?.into_iter().map(|q| local.transform_point3(q)));
        }
        if k == with {
            others = pts;
        } else if !pts.is_empty() {
            corners = vertices(&minkowski(&corners, &vertices(&pts)?)?)?;
        }
    }
    let centres: Vec<DVec3> = discs.iter().map(|d| d.0).collect();
    let tol = crate::geometry::polytope::points_tolerance(&centres);
    if !others.is_empty() {
        let near = 1e-9 * scale(&centres).max(1.0);
        let hull = super::quickhull::hull(&centres, tol);
        let inside = |q: DVec3| {
            hull.as_ref().is_some_and(|(v, t)| {
                t.iter().all(|f| {
                    let [a, b, c] = f.map(|i| v[i as usize]);
                    let n = (b - a).cross(c - a).normalize_or_zero();
                    (q - a).dot(n) <= near
                })
            }) || axis_ends.iter().any(|&[a, b]| in_frustum(q, a, b, near))
        };
        // A corner outside is a disc of radius zero: the hull of discs
        // and points is the same union of pieces.
        for &q in others.iter().filter(|&&q| !inside(q)) {
            discs.push((q, 0.0));
        }
    }
    let mut all: Vec<Disc> = Vec::new();
    for &(c, r) in &discs {
        for &q in &corners {
            let d = (c + q, r);
            if !all
                .iter()
                .any(|e| (e.0 - d.0).abs().max_element() <= tol && (e.1 - d.1).abs() <= tol)
            {
                all.push(d);
            }
        }
    }
    if all.len() > MAX_HULL_POINTS {
        return None;
    }
    pieces(&all, tol, &frame, l)
}

/// The pieces of the hull of `discs` (in the discs' frame), placed in the
/// world by `frame` (whose linear part is `l`).
fn pieces(discs: &[Disc], tol: f64, frame: &DAffine3, l: DMat3) -> Option<Pieces> {
    let world = |p: DVec3| frame.transform_point3(p);
    let mut out = Pieces { parts: Vec::new() };
    let centres: Vec<DVec3> = discs.iter().map(|d| world(d.0)).collect();
    if let Some(mesh) = super::polytope::hull_mesh(&centres) {
        out.parts.push((Shape::Mesh(mesh), DAffine3::IDENTITY));
    }
    let n = discs.len();
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = (discs[i], discs[j]);
            if (b.0.z - a.0.z).abs() <= tol || a.1.max(b.1) <= tol || !exposed(discs, i, j) {
                continue;
            }
            let m = DAffine3::from_mat3_translation(
                DMat3::from_cols(l.x_axis, l.y_axis, l * (b.0 - a.0)),
                world(a.0),
            );
            // The fault: each frustum's far disc 1 % small.
            let thin = if crate::mutant::active("disc_hull_frustum_thin") {
                0.99
            } else {
                1.0
            };
            let cone = Cone {
                r0: a.1,
                r1: b.1 * thin,
                centered: false,
            };
            out.parts.push((Shape::Cone(cone), m));
        }
    }
    // The faces made so far: their discs and horizontal normal (the same
    // discs touch two planes, one on each side, when they are three).
    let mut faces: Vec<(Vec<usize>, DVec3)> = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                for u in touching(discs, [i, j, k], tol) {
                    let on: Vec<usize> = (0..n).filter(|&m| u.1[m]).collect();
                    if faces
                        .iter()
                        .any(|f| f.0 == on && (f.1 - u.0).length() <= 1e-9)
                    {
                        continue;
                    }
                    let pts: Vec<DVec3> = on
                        .iter()
                        .flat_map(|&m| {
                            let (c, r) = discs[m];
                            [world(c), world(c + u.0 * r)]
                        })
                        .collect();
                    if let Some(mesh) = super::polytope::hull_mesh(&pts) {
                        out.parts.push((Shape::Mesh(mesh), DAffine3::IDENTITY));
                    }
                    faces.push((on, u.0));
                }
            }
        }
    }
    (!out.parts.is_empty()).then_some(out)
}

/// Whether the pair (i, j) is farthest along some (u, w) — u a unit
/// horizontal vector at angle θ, w the slope that makes the two discs
/// equally far — over an open set of θ: the support h(u, w) = u·c + w·z + ρ
/// of every other disc k at most theirs, each an arc of θ (α cos θ + β sin
/// θ + γ ≥ 0), and their intersection longer than 10⁻⁹.
fn exposed(discs: &[Disc], i: usize, j: usize) -> bool {
    let (ci, ri) = discs[i];
    let d = ci - discs[j].0;
    let dr = ri - discs[j].1;
    let mut arcs: Vec<(f64, f64)> = vec![(0.0, std::f64::consts::TAU)];
    for (k, &(ck, rk)) in discs.iter().enumerate() {
        if k == i || k == j {
            continue;
        }
        let e = ci - ck;
        let f = e.z / d.z;
        let (alpha, beta, gamma) = (e.x - d.x * f, e.y - d.y * f, (ri - rk) - dr * f);
        let r = alpha.hypot(beta);
        if gamma >= r {
            continue;
        }
        if gamma <= -r {
            return false;
        }
        let mid = beta.atan2(alpha);
        let half = (-gamma / r).acos();
        arcs = intersect(&arcs, mid - half, mid + half);
        if arcs.is_empty() {
            return false;
        }
    }
    arcs.iter().map(|(a, b)| b - a).sum::<f64>() > 1e-9
}

/// `arcs` (disjoint, within [0, 2π]) cut to the arc from `lo` to `hi`
/// (at most a turn).
fn intersect(arcs: &[(f64, f64)], lo: f64, hi: f64) -> Vec<(f64, f64)> {
    let tau = std::f64::consts::TAU;
    let width = hi - lo;
    let lo = lo.rem_euclid(tau);
    let mut out = Vec::new();
    for &(a, b) in arcs {
        for shift in [0.0, -tau] {
            let (x, y) = (a.max(lo + shift), b.min(lo + width + shift));
            if x < y {
                out.push((x, y));
            }
        }
    }
    out
}

/// The planes touching discs i, j and k with every disc on one side: each
/// as its normal made horizontal and the discs it touches.
fn touching(discs: &[Disc], ids: [usize; 3], tol: f64) -> Vec<(DVec3, Vec<bool>)> {
    let [i, j, k] = ids.map(|m| discs[m]);
    // n = (x, y, w) with n·(cᵢ − c) + ρᵢ − ρ = 0 for the other two: a line
    // of n, met with x² + y² = 1.
    let r1 = i.0 - j.0;
    let r2 = i.0 - k.0;
    let (e1, e2) = (j.1 - i.1, k.1 - i.1);
    let v = r1.cross(r2);
    let vv = v.length_squared();
    if vv <= 1e-24 * r1.length_squared() * r2.length_squared() {
        return Vec::new();
    }
    let p0 = ((r1 * (e1 * r2.length_squared() - e2 * r1.dot(r2)))
        + r2 * (e2 * r1.length_squared() - e1 * r1.dot(r2)))
        / vv;
    let qa = v.x * v.x + v.y * v.y;
    let qb = p0.x * v.x + p0.y * v.y;
    let qc = p0.x * p0.x + p0.y * p0.y - 1.0;
    let disc = qb * qb - qa * qc;
    if qa <= 0.0 || disc < 0.0 {
        return Vec::new();
    }
    let root = disc.sqrt();
    let mut out = Vec::new();
    for t in [(-qb - root) / qa, (-qb + root) / qa] {
        let n = p0 + v * t;
        let h = |d: &Disc| n.dot(d.0) + d.1;
        let top = h(&i);
        let slack = tol * n.length();
        if discs.iter().any(|d| h(d) > top + slack) {
            continue;
        }
        let on = discs.iter().map(|d| h(d) >= top - slack).collect();
        out.push((DVec3::new(n.x, n.y, 0.0).normalize(), on));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cone(at: DVec3, r0: f64, r1: f64, h: f64) -> ConvexPart {
        ConvexPart {
            shape: Shape::Cone(Cone {
                r0,
                r1,
                centered: false,
            }),
            to_world: DAffine3::from_scale_rotation_translation(
                DVec3::new(1.0, 1.0, h),
                glam::DQuat::IDENTITY,
                at,
            ),
        }
    }

    #[test]
    fn two_discs_are_one_frustum_and_the_centres_segment() {
        // A cylinder r = 2 under a disc r = 1 off to the side: the hull is
        // the cylinder's two discs and the top disc; every pair at two
        // heights is on the boundary, and the triples touch two planes.
        let p = as_disc_hull(&[vec![
            cone(DVec3::ZERO, 2.0, 2.0, 1.0),
            cone(DVec3::new(3.0, 0.0, 4.0), 1.0, 1.0, 0.0001),
        ]])
        .unwrap();
        let cones = p
            .parts
            .iter()
            .filter(|(s, _)| s.name() == "cylinder")
            .count();
        assert!(cones >= 3, "{cones} frustums");
    }

    /// Hulls of upright cylinders and cones (one disc scaled) with boxes
    /// whose corners lie outside them (a tab: a boss hulled with a plate),
    /// against the hull of the discs' circles at 720 points each and the
    /// boxes' corners, which lies inside the exact hull and within the
    /// circles' sagitta of it: 60 random sets, 400 points each; a point
    /// inside the sampled hull is in one of the pieces, a point farther
    /// than the sagitta outside it in none.
    #[test]
    fn discs_hulled_with_boxes_are_their_sampled_hull() {
        use crate::geometry::Cuboid;
        let mut rnd = crate::plane::tests::uniform(21);
        let n = 720;
        let (mut inside, mut outside) = (0, 0);
        for set in 0..60 {
            let mut parts = Vec::new();
            let mut pts = Vec::new();
            let (lo, hi) = (3.0 * rnd(), 3.0 + 4.0 * rnd());
            for _ in 0..1 + set % 3 {
                let r = 0.5 + 2.0 * rnd();
                let top = if set % 2 == 0 {
                    r
                } else {
                    r * (0.3 + 0.7 * rnd())
                };
                let (z, h) = if set % 4 < 2 {
                    (lo, hi - lo)
                } else {
                    (5.0 * rnd(), 0.5 + 4.0 * rnd())
                };
                let at = DVec3::new(8.0 * rnd() - 4.0, 8.0 * rnd() - 4.0, z);
                parts.push(cone(at, r, top, h));
                for k in 0..n {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    let u = DVec3::new(a.cos(), a.sin(), 0.0);
                    pts.push(at + u * r);
                    pts.push(at + u * top + DVec3::Z * h);
                }
            }
            for _ in 0..1 + set % 2 {
                let size = DVec3::new(1.0 + 6.0 * rnd(), 0.5 + 3.0 * rnd(), hi - lo);
                let at = DVec3::new(10.0 * rnd() - 5.0, 10.0 * rnd() - 5.0, lo);
                let m = DAffine3::from_scale_rotation_translation(size, glam::DQuat::IDENTITY, at);
                let part = ConvexPart {
                    shape: Shape::Cuboid(Cuboid { centered: false }),
                    to_world: m,
                };
                pts.extend(part.corners().unwrap());
                parts.push(part);
            }
            let pieces = as_disc_hull(&[parts]).unwrap_or_else(|| panic!("set {set}: no pieces"));
            let sagitta = 2.5 * (1.0 - (std::f64::consts::PI / n as f64).cos());
            let what = format!("set {set}");
            let (i, o) = pieces.check_sampled_hull(&pts, 2.0 * sagitta, 400, &mut rnd, &what);
            (inside, outside) = (inside + i, outside + o);
        }
        assert!(
            inside > 5000 && outside > 5000,
            "{inside} inside, {outside} outside"
        );
    }

    #[test]
    fn arcs_are_cut_across_zero() {
        let tau = std::f64::consts::TAU;
        let a = intersect(&[(0.0, tau)], -0.5, 0.5);
        let total: f64 = a.iter().map(|(x, y)| y - x).sum();
        assert!((total - 1.0).abs() < 1e-12, "{a:?}");
        let b = intersect(&a, 0.25, 3.0);
        let total: f64 = b.iter().map(|(x, y)| y - x).sum();
        assert!((total - 0.25).abs() < 1e-12, "{b:?}");
    }
}
