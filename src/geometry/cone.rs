//! Cylinders and cone frusta: z from `z0` to `z0 + 1` (z0 = −½ when
//! centred, else 0), radius `r0` at the bottom and `r1` at the top (the
//! larger being 1), an apex where a radius is 0.
//! `cylinder(h, r1, r2, center)` is this solid scaled by (r, r, h).
//!
//! The solid is convex, so the line meets it in one interval: the part of
//! {x² + y² ≤ r(z)²} (one or two pieces of the line, found with a stable
//! quadratic) that lies in the slab 0 ≤ z ≤ 1. Inside the slab r(z) ≥ 0, so
//! the other nappe of the double cone never leaks in. Parts: 0 = side,
//! 1 = bottom cap, 2 = top cap.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use glam::{DAffine3, DVec3};

/// A cone frustum: z in [0, 1] (or [-½, ½] when centred), radius `r0` at
/// the bottom and `r1` at the top, the larger of the two being 1. A
/// cylinder has both 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    pub r0: f64,
    pub r1: f64,
    pub centered: bool,
}

impl Solid for Cone {
    const NAME: &'static str = "cylinder";

    #[inline]
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        spans(self.r0, self.r1, bottom(self.centered), q.o, q.d, emit)
    }

    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        normal(self.r0, self.r1, bottom(self.centered), p, part)
    }

    fn contains(&self, p: DVec3) -> bool {
        let z = p.z - bottom(self.centered);
        (0.0..=1.0).contains(&z) && p.truncate().length() <= self.r0 + (self.r1 - self.r0) * z
    }

    fn object_bounds(&self) -> Aabb {
        let z0 = bottom(self.centered);
        Aabb::new(DVec3::new(-1.0, -1.0, z0), DVec3::new(1.0, 1.0, z0 + 1.0))
    }

    /// Exact: the hull of the two elliptic discs the caps become.
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        let col = |i: usize| m.matrix3.col(i);
        let (u, v) = (col(0), col(1));
        let e = (u * u + v * v).powf(0.5);
        let z0 = bottom(self.centered);
        let c0 = m.transform_point3(DVec3::new(0.0, 0.0, z0));
        let c1 = m.transform_point3(DVec3::new(0.0, 0.0, z0 + 1.0));
        Aabb::new(c0 - e * self.r0, c0 + e * self.r0)
            .union(&Aabb::new(c1 - e * self.r1, c1 + e * self.r1))
    }

    /// The farther of the two cap discs' supports.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let z0 = bottom(self.centered);
        let flat = d.truncate();
        let dir = if flat == glam::DVec2::ZERO {
            glam::DVec2::ZERO
        } else {
            flat.normalize()
        };
        let bottom = (dir * self.r0).extend(z0);
        let top = (dir * self.r1).extend(z0 + 1.0);
        Some(if top.dot(d) > bottom.dot(d) {
            top
        } else {
            bottom
        })
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("r0", Param::Num(self.r0)),
            ("r1", Param::Num(self.r1)),
            ("centered", Param::Bool(self.centered)),
        ]
    }

    fn pov(&self) -> String {
        let (r0, r1) = (self.r0, self.r1);
        let z0 = bottom(self.centered);
        if r0 == r1 {
            format!("cylinder {{ <0, 0, {z0:?}>, <0, 0, {:?}>, {r0:?}", z0 + 1.0)
        } else {
            format!(
                "cone {{ <0, 0, {z0:?}>, {r0:?}, <0, 0, {:?}>, {r1:?}",
                z0 + 1.0
            )
        }
    }
}

const SIDE: Part = 0;
const BOTTOM: Part = 1;
const TOP: Part = 2;

/// The z of the bottom cap.
pub fn bottom(centered: bool) -> f64 {
    if centered {
        -0.5
    } else {
        0.0
    }
}

pub fn spans(r0: f64, r1: f64, z0: f64, o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    // Solve from the line's closest approach to the solid's centre, so that
    // a far origin does not make the coefficients huge and cancel; the
    // shift is added back to every t. Heights are measured from the bottom.
    let shift = -(o - DVec3::new(0.0, 0.0, z0 + 0.5)).dot(d) / d.length_squared();
    let o = o + shift * d - DVec3::new(0.0, 0.0, z0);
    if let Some((t0, p0, t1, p1)) = span(r0, r1, o, d) {
        emit((t0 + shift, p0, t1 + shift, p1));
    }
}

/// The one span of the convex solid along `o + t·d` (heights from the
/// bottom cap), if any.
fn span(r0: f64, r1: f64, o: DVec3, d: DVec3) -> Option<RawSpan> {
    // The slab 0 ≤ z ≤ 1.
    let slab = if d.z == 0.0 {
        if o.z <= 0.0 || o.z >= 1.0 {
            return None;
        }
        (f64::NEG_INFINITY, BOTTOM, f64::INFINITY, TOP)
    } else {
        let tb = -o.z / d.z;
        let tt = (1.0 - o.z) / d.z;
        if tb < tt {
            (tb, BOTTOM, tt, TOP)
        } else {
            (tt, TOP, tb, BOTTOM)
        }
    };
    // The side: f(t) = A t² + 2B t + C ≤ 0.
    let k = r1 - r0;
    let r_o = r0 + k * o.z;
    let a = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    let b = o.x * d.x + o.y * d.y - k * d.z * r_o;
    let c = o.x * o.x + o.y * o.y - r_o * r_o;
    let all = (f64::NEG_INFINITY, f64::INFINITY);
    if a == 0.0 {
        return if b > 0.0 {
            clip((f64::NEG_INFINITY, -c / (2.0 * b)), slab)
        } else if b < 0.0 {
            clip((-c / (2.0 * b), f64::INFINITY), slab)
        } else if c < 0.0 {
            clip(all, slab)
        } else {
            None
        };
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return if a < 0.0 { clip(all, slab) } else { None };
    }
    let q = -(b + disc.sqrt().copysign(b));
    let (mut lo, mut hi) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    if lo > hi {
        std::mem::swap(&mut lo, &mut hi);
    }
    if a > 0.0 {
        return clip((lo, hi), slab);
    }
    // Two pieces, one on each nappe; only one can meet the slab, but near
    // an apex rounding may let both: keep their hull then.
    match (
        clip((f64::NEG_INFINITY, lo), slab),
        clip((hi, f64::INFINITY), slab),
    ) {
        (Some(g), Some(s)) => Some((g.0, g.1, s.2, s.3)),
        (g, s) => g.or(s),
    }
}

/// The part of the side interval `(s0, s1)` inside the slab, its ends
/// marked by the surface that bounds them.
#[inline]
fn clip((s0, s1): (f64, f64), (z0, zp0, z1, zp1): RawSpan) -> Option<RawSpan> {
    let (t0, p0) = if s0 > z0 { (s0, SIDE) } else { (z0, zp0) };
    let (t1, p1) = if s1 < z1 { (s1, SIDE) } else { (z1, zp1) };
    (t0 < t1).then_some((t0, p0, t1, p1))
}

pub fn normal(r0: f64, r1: f64, z0: f64, p: DVec3, part: Part) -> DVec3 {
    match part {
        BOTTOM => DVec3::NEG_Z,
        TOP => DVec3::Z,
        _ => {
            let k = r1 - r0;
            let n = DVec3::new(p.x, p.y, -(r0 + k * (p.z - z0)) * k);
            if n == DVec3::ZERO {
                // The apex itself: the axis is as good a normal as any.
                DVec3::new(0.0, 0.0, -k.signum())
            } else {
                n
            }
        }
    }
}
