//! Hulls of cylinders and cones on one axis, written out as what they are:
//! a solid of revolution ([`Lathe`]) of a straight profile.
//!
//! A set turned about an axis has a hull turned about it too, and the
//! hull's section by a half-plane through the axis is the right half of
//! the hull of the sets' full sections: the section of a hull contains the
//! hull of the sections, and the projection onto that plane of the hull
//! (the hull of the projection) lies in the hull of the sections, since a
//! point's projection lies between it and its mirror image in the plane.
//! A cone frustum's section is a trapezoid, so the hull of coaxial
//! frustums is the turn of the hull of their rims' points and of the axis
//! between the lowest and the highest of them: straight edges only,
//! each a cone, a cylinder or a disc of the lathe.

use super::ball_sum::{ball_of, Pieces};
use super::convex::ConvexPart;
use super::lathe::Lathe;
use super::{Shape, Sphere, Torus};
use crate::plane::{Outlines, Region};
use glam::{DAffine3, DMat3, DVec2, DVec3};
use std::sync::Arc;

/// A cone frustum placed with circular sections: its axis (unit), its
/// bottom and top centres, and their radii.
#[derive(Clone, Copy, Debug)]
pub struct PlacedCone {
    pub axis: DVec3,
    pub bottom: DVec3,
    pub top: DVec3,
    pub r_bottom: f64,
    pub r_top: f64,
}

/// Whether `v` is within 10⁻¹² of `of` of zero: a point on the axis, to
/// the rounding of the arithmetic.
fn tight(v: f64, of: f64) -> bool {
    v.abs() <= 1e-12 * of
}

/// Whether `v` is within [`EXPORT_ROUNDING`] of `of` of zero: the test of
/// a placement's right angles and equal lengths.
fn square(v: f64, of: f64) -> bool {
    v.abs() <= EXPORT_ROUNDING * of
}

/// How far from square and even a part's placement may be and still be
/// taken as a rotation and a uniform scale (relative to its scale): the
/// CSG export writes matrices to 6 significant digits, so a rotation comes
/// back square to about 10⁻⁶ (`rotate([0, 0, 36])` as 0.809017 and
/// 0.587785: rows of length 1 − 1.4·10⁻⁷). Within this, the part is what
/// the model said — a sphere a ball, a cylinder circular — as OpenSCAD's
/// own render from the `.scad` has it; the file's rounded matrix differs
/// from it by at most this fraction of the part's size.
pub const EXPORT_ROUNDING: f64 = 1e-5;

/// The part as a frustum whose sections across its axis are circles (its
/// transform a rotation, a uniform scale across the axis and any length
/// along it, within [`EXPORT_ROUNDING`]), or `None`.
pub fn placed_cone(p: &ConvexPart) -> Option<PlacedCone> {
    let Shape::Cone(c) = &p.shape else {
        return None;
    };
    let m = p.to_world.matrix3;
    let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
    let (lx, lz) = (x.length(), z.length());
    if !(lx > 0.0
        && lz > 0.0
        && square(x.dot(y), lx * lx)
        && square(y.length() - lx, lx)
        && square(x.dot(z), lx * lz)
        && square(y.dot(z), lx * lz))
    {
        return None;
    }
    let z0 = super::cone::bottom(c.centered);
    Some(PlacedCone {
        axis: z / lz,
        bottom: p.to_world.transform_point3(DVec3::Z * z0),
        top: p.to_world.transform_point3(DVec3::Z * (z0 + 1.0)),
        r_bottom: lx * c.r0,
        r_top: lx * c.r1,
    })
}

/// The hull (one hull, not a sum) of frustums on one axis as a lathe and
/// its placement (the lathe's z along the axis); `None` when a part is
/// anything else, off the axis (10⁻¹² of the parts' size), or the hull has
/// no volume.
pub fn as_lathe(hulls: &[Vec<ConvexPart>]) -> Option<(Lathe, DAffine3)> {
    let [parts] = hulls else { return None };
    let (profile, place) = profile(parts)?;
    let region = Region::new(Outlines::polygons(vec![profile]));
    Some((Lathe::new(Arc::new(region)), place))
}

/// The profile (radius, height; counter-clockwise, its edge on the axis
/// included) of the hull of `parts`, frustums on one axis, and the
/// placement of the axis (z along it); `None` as for [`as_lathe`].
fn profile(parts: &[ConvexPart]) -> Option<(Vec<DVec2>, DAffine3)> {
    let cones: Vec<PlacedCone> = parts.iter().map(placed_cone).collect::<Option<_>>()?;
    let first = cones.first()?;
    let (a, o) = (first.axis, first.bottom);
    let size = cones
        .iter()
        .map(|c| (c.top - o).length().max((c.bottom - o).length()) + c.r_bottom.max(c.r_top))
        .fold(0.0, f64::max);
    let mut pts = Vec::with_capacity(2 * cones.len() + 2);
    for c in &cones {
        for (q, r) in [(c.bottom, c.r_bottom), (c.top, c.r_top)] {
            // On the axis: no more than the rounding away from it.
            if !tight((q - o).reject_from_normalized(a).length(), size) {
                return None;
            }
            pts.push(DVec2::new(r, (q - o).dot(a)));
        }
    }
    let (lo, hi) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (l.min(p.y), h.max(p.y))
        });
    if !crate::mutant::active("coaxial_axis_dropped") {
        pts.push(DVec2::new(0.0, lo));
        pts.push(DVec2::new(0.0, hi));
    }
    let corners = crate::plane::hull::hull_indices_2d(&pts, 1e-12);
    if corners.len() < 3 || hi <= lo || pts.iter().all(|p| p.x <= 0.0) {
        return None;
    }
    let profile: Vec<DVec2> = corners.iter().map(|&i| pts[i]).collect();
    let u = a.any_orthonormal_vector();
    let place = DAffine3::from_mat3_translation(DMat3::from_cols(u, a.cross(u), a), o);
    Some((profile, place))
}

/// A hull of frustums on one axis plus a ball (OpenSCAD's rounded
/// cylinder, `minkowski() { cylinder(…); sphere(…); }`) as exact pieces:
/// the set is turned, so its section through the axis is the hull's
/// profile offset by the ball's radius ρ (a point's nearest point of a
/// turned set lies in the point's own half-plane), and a convex polygon
/// offset is the polygon with each edge pushed out by ρ and a disc about
/// each corner. Turned: one lathe of the profile with its edges (but the
/// one on the axis) pushed out, joined at each corner by the two walls
/// from it, a torus about each corner off the axis and a ball at a corner
/// on it where the edge leaving the axis is not square to it. Placed in
/// the parts' frame.
pub fn as_rounded_lathe(hulls: &[Vec<ConvexPart>]) -> Option<Pieces> {
    let [a, b] = hulls else { return None };
    let ((c, r), parts) = match (ball_of(a), ball_of(b)) {
        (_, Some(ball)) => (ball, a),
        (Some(ball), None) => (ball, b),
        _ => return None,
    };
    let (mut profile, place) = profile(parts)?;
    let place = DAffine3::from_translation(c) * place;
    let twice_area: f64 = (0..profile.len())
        .map(|i| profile[i].perp_dot(profile[(i + 1) % profile.len()]))
        .sum();
    if twice_area < 0.0 {
        profile.reverse();
    }
    let size = profile
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    let on_axis = |p: DVec2| p.x <= 1e-12 * size;
    let k = profile.len();
    // Each edge's outward normal, or none for the edge on the axis.
    let push: Vec<Option<DVec2>> = (0..k)
        .map(|i| {
            let (p, q) = (profile[i], profile[(i + 1) % k]);
            (!(on_axis(p) && on_axis(q))).then(|| DVec2::new(q.y - p.y, p.x - q.x).normalize() * r)
        })
        .collect();
    let mut outline: Vec<DVec2> = Vec::with_capacity(3 * k);
    let mut out = Pieces { parts: Vec::new() };
    for i in 0..k {
        let p = profile[i];
        let (before, after) = (push[(i + k - 1) % k], push[i]);
        outline.extend(before.map(|n| p + n));
        outline.push(p);
        outline.extend(after.map(|n| p + n));
        let leaves = before.or(after).expect("one edge off the axis");
        let at = |m: DMat3| place * DAffine3::from_mat3_translation(m, DVec3::Z * p.y);
        if !on_axis(p) {
            let m = DMat3::from_diagonal(DVec3::splat(p.x));
            // The fault: each rim's torus 1 % thin.
            let minor = if crate::mutant::active("rounded_lathe_torus_thin") {
                0.99 * r / p.x
            } else {
                r / p.x
            };
            out.parts.push((Shape::Torus(Torus { minor }), at(m)));
        } else if leaves.y.abs() > 1e-12 * r {
            out.parts.push((
                Shape::Sphere(Sphere),
                at(DMat3::from_diagonal(DVec3::splat(r))),
            ));
        }
    }
    outline.dedup();
    let region = Region::new(Outlines::polygons(vec![outline]));
    out.parts
        .push((Shape::Lathe(Lathe::new(Arc::new(region))), place));
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::cone::Cone;
    use crate::geometry::solid::Solid;

    fn cone(r0: f64, r1: f64, h: f64, z: f64, r: f64) -> ConvexPart {
        let (r0, r1) = (r0 / r, r1 / r);
        ConvexPart {
            shape: Shape::Cone(Cone {
                r0,
                r1,
                centered: false,
            }),
            to_world: DAffine3::from_translation(DVec3::new(1.0, 2.0, z))
                * DAffine3::from_scale(DVec3::new(r, r, h)),
        }
    }

    /// A point is in the hull of two coaxial cylinders where it is in the
    /// cone frustum between the wider one's rim and the other's (the
    /// closed form of this pair): checked at points of a grid.
    #[test]
    fn two_coaxial_cylinders_hull_to_their_frustum() {
        // r = 3 over z in [0, 1]; r = 1 over z in [0, 5]: the hull is the
        // r = 3 cylinder below z = 1, the frustum from r = 3 at z = 1 to
        // r = 1 at z = 5 above.
        let parts = vec![cone(3.0, 3.0, 1.0, 0.0, 3.0), cone(1.0, 1.0, 5.0, 0.0, 1.0)];
        let (lathe, place) = as_lathe(&[parts]).expect("coaxial");
        let inv = place.inverse();
        let inside = |x: f64, y: f64, z: f64| {
            let rho = ((x - 1.0).powi(2) + (y - 2.0).powi(2)).sqrt();
            let r = if z <= 1.0 { 3.0 } else { 3.0 - 0.5 * (z - 1.0) };
            (0.0..=5.0).contains(&z) && rho <= r
        };
        let mut checked = 0;
        for i in 0..24 {
            for k in 0..28 {
                let (x, z) = (
                    1.0 - 3.5 + 7.0 * (i as f64 + 0.37) / 24.0,
                    -0.7 + 6.4 * (k as f64 + 0.41) / 28.0,
                );
                let y = 2.0 + 0.3 * x;
                let p = inv.transform_point3(DVec3::new(x, y, z));
                assert_eq!(lathe.contains(p), inside(x, y, z), "at {x} {y} {z}");
                checked += 1;
            }
        }
        assert_eq!(checked, 24 * 28);
    }

    #[test]
    fn off_the_axis_is_not_a_lathe() {
        let mut b = cone(1.0, 1.0, 2.0, 0.0, 1.0);
        b.to_world = DAffine3::from_translation(DVec3::X * 1e-6) * b.to_world;
        assert!(as_lathe(&[vec![cone(2.0, 1.0, 1.0, 0.0, 2.0), b]]).is_none());
    }
}
