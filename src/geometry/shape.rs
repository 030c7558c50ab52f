//! The closed set of primitive shapes, matched rather than boxed.
//!
//! Each shape answers, in object space: the spans (entry, exit) of the whole
//! line `o + t·d` inside it, sorted; the outward normal at a surface point;
//! whether a point is inside; and its bounding box.

use super::{cone, cuboid, halfspace, sphere, torus, Aabb, Part};
use glam::{DAffine3, DVec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// The unit sphere at the origin.
    Sphere,
    /// The cube [-1, 1]³ when centred, else [0, 1]³.
    ///
    /// Centring lives in the object space, not in the transform, so that a
    /// part's world translation is exactly the one the file gives: a
    /// `cube(0.001)` at 1e6 would otherwise sit at 1e6 + 0.0005, rounded to
    /// an ulp of 1e6, which is 6e-8 of its size.
    Cuboid { centered: bool },
    /// A cone frustum: z in [0, 1] (or [-½, ½] when centred), radius `r0`
    /// at the bottom and `r1` at the top, the larger of the two being 1. A
    /// cylinder has both 1.
    Cone { r0: f64, r1: f64, centered: bool },
    /// A torus around the z axis, major radius 1, tube radius `minor` < 1.
    Torus { minor: f64 },
    /// The half-space z ≤ 0.
    Halfspace,
}

/// Where the line enters and leaves a solid: `(t_in, part_in, t_out, part_out)`.
pub type RawSpan = (f64, Part, f64, Part);

impl Shape {
    pub const fn name(&self) -> &'static str {
        match self {
            Shape::Sphere => "sphere",
            Shape::Cuboid { .. } => "cube",
            Shape::Cone { .. } => "cylinder",
            Shape::Torus { .. } => "torus",
            Shape::Halfspace => "halfspace",
        }
    }

    /// Calls `emit` for each span of the line `o + t·d` inside the solid, in
    /// increasing `t`. Spans are never empty (`t_in < t_out`); unbounded
    /// ends are ±∞ with part [`super::NO_PART`].
    #[inline]
    pub fn spans(&self, o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
        match *self {
            Shape::Sphere => sphere::spans(o, d, emit),
            Shape::Cuboid { centered } => cuboid::spans(cuboid::low(centered), o, d, emit),
            Shape::Cone { r0, r1, centered } => {
                cone::spans(r0, r1, cone::bottom(centered), o, d, emit)
            }
            Shape::Torus { minor } => torus::spans(minor, o, d, emit),
            Shape::Halfspace => halfspace::spans(o, d, emit),
        }
    }

    /// The outward (not unit) normal at object-space point `p` on `part`.
    pub fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        match *self {
            Shape::Sphere => p,
            Shape::Cuboid { .. } => cuboid::normal(part),
            Shape::Cone { r0, r1, centered } => {
                cone::normal(r0, r1, cone::bottom(centered), p, part)
            }
            Shape::Torus { .. } => torus::normal(p),
            Shape::Halfspace => DVec3::Z,
        }
    }

    /// Whether object-space point `p` is inside (boundary counts as inside).
    pub fn contains(&self, p: DVec3) -> bool {
        match *self {
            Shape::Sphere => p.length_squared() <= 1.0,
            Shape::Cuboid { centered } => {
                let lo = cuboid::low(centered);
                p.min_element() >= lo && p.max_element() <= 1.0
            }
            Shape::Cone { r0, r1, centered } => {
                let z = p.z - cone::bottom(centered);
                (0.0..=1.0).contains(&z) && p.truncate().length() <= r0 + (r1 - r0) * z
            }
            Shape::Torus { minor } => {
                let q = p.truncate().length() - 1.0;
                q * q + p.z * p.z <= minor * minor
            }
            Shape::Halfspace => p.z <= 0.0,
        }
    }

    /// A box around the solid in object space.
    pub fn object_bounds(&self) -> Aabb {
        match *self {
            Shape::Sphere => Aabb::new(DVec3::NEG_ONE, DVec3::ONE),
            Shape::Cuboid { centered } => {
                Aabb::new(DVec3::splat(cuboid::low(centered)), DVec3::ONE)
            }
            Shape::Cone { centered, .. } => {
                let z0 = cone::bottom(centered);
                Aabb::new(DVec3::new(-1.0, -1.0, z0), DVec3::new(1.0, 1.0, z0 + 1.0))
            }
            Shape::Torus { minor } => {
                let e = DVec3::new(1.0 + minor, 1.0 + minor, minor);
                Aabb::new(-e, e)
            }
            Shape::Halfspace => Aabb::EVERYTHING,
        }
    }

    /// A tight world box of the solid under `m`: exact for spheres
    /// (ellipsoids), cone frusta (the hull of two elliptic discs) and tori
    /// (a circle swept by a ball), one-sided for half-spaces with an
    /// axis-aligned plane, the transformed object box for cubes.
    pub fn world_bounds(&self, m: &DAffine3) -> Aabb {
        let col = |i: usize| m.matrix3.col(i);
        match *self {
            Shape::Sphere => {
                let (a, b, c) = (col(0), col(1), col(2));
                let e = (a * a + b * b + c * c).powf(0.5);
                Aabb::new(m.translation - e, m.translation + e)
            }
            Shape::Cone { r0, r1, centered } => {
                let (u, v) = (col(0), col(1));
                let e = (u * u + v * v).powf(0.5);
                let z0 = cone::bottom(centered);
                let c0 = m.transform_point3(DVec3::new(0.0, 0.0, z0));
                let c1 = m.transform_point3(DVec3::new(0.0, 0.0, z0 + 1.0));
                Aabb::new(c0 - e * r0, c0 + e * r0).union(&Aabb::new(c1 - e * r1, c1 + e * r1))
            }
            Shape::Torus { minor } => {
                // The torus is the core circle ⊕ a ball of radius `minor`,
                // and a linear map keeps Minkowski sums: the half-extents
                // add, the ellipse's √(u² + v²) and the ellipsoid's
                // minor·|row|.
                let (u, v, w) = (col(0), col(1), col(2));
                let e = (u * u + v * v).powf(0.5) + minor * (u * u + v * v + w * w).powf(0.5);
                Aabb::new(m.translation - e, m.translation + e)
            }
            Shape::Halfspace => {
                // Bounded on one side when the plane is axis-aligned (a
                // floor): the solid is n·(p − c) ≤ 0 for the world normal n.
                let n = m.matrix3.inverse().transpose() * DVec3::Z;
                let mut b = Aabb::EVERYTHING;
                let axes = (0..3).filter(|&i| n[i] != 0.0).collect::<Vec<_>>();
                if let [i] = axes[..] {
                    if n[i] > 0.0 {
                        b.max[i] = m.translation[i];
                    } else {
                        b.min[i] = m.translation[i];
                    }
                }
                b
            }
            _ => {
                let b = self.object_bounds();
                let mut out = Aabb::EMPTY;
                for i in 0..8 {
                    let p = DVec3::new(
                        if i & 1 == 0 { b.min.x } else { b.max.x },
                        if i & 2 == 0 { b.min.y } else { b.max.y },
                        if i & 4 == 0 { b.min.z } else { b.max.z },
                    );
                    out = out.include(m.transform_point3(p));
                }
                out
            }
        }
    }
}
