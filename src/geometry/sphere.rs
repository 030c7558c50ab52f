//! The unit sphere at the origin: `sphere(r = 1)`, `sphere(d = 2)`.
//!
//! Solves |o + t·d|² = 1 with the stable discriminant of Ray Tracing Gems
//! ch. 7: b² − ac = a·(1 − |o − (b/a)·d|²), which does not cancel when the
//! ray passes far from the sphere, and the roots as q/a and c/q so that
//! neither suffers cancellation.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use glam::{DAffine3, DVec3};

/// The unit sphere at the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere;

impl Solid for Sphere {
    const NAME: &'static str = "sphere";

    #[inline]
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        spans(q.o, q.d, emit)
    }

    fn normal(&self, p: DVec3, _part: Part) -> DVec3 {
        p
    }

    fn contains(&self, p: DVec3) -> bool {
        p.length_squared() <= 1.0
    }

    fn object_bounds(&self) -> Aabb {
        Aabb::new(DVec3::NEG_ONE, DVec3::ONE)
    }

    /// Exact: the ellipsoid's half-extent along each world axis is the
    /// length of that row of the matrix.
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        let col = |i: usize| m.matrix3.col(i);
        let (a, b, c) = (col(0), col(1), col(2));
        let e = (a * a + b * b + c * c).powf(0.5);
        Aabb::new(m.translation - e, m.translation + e)
    }

    fn support(&self, d: DVec3) -> Option<DVec3> {
        Some(d.normalize())
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![]
    }

    fn pov(&self) -> String {
        "sphere { <0, 0, 0>, 1".to_string()
    }
}

pub fn spans(o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    let a = d.length_squared();
    let inv_a = 1.0 / a;
    let b = o.dot(d); // half the linear coefficient
    let l = o - (b * inv_a) * d; // the line's closest point to the centre
    let disc = a * (1.0 - l.length_squared());
    if disc <= 0.0 || !disc.is_finite() {
        return;
    }
    let c = o.length_squared() - 1.0;
    let q = -(b + disc.sqrt().copysign(b));
    let (t0, t1) = (q * inv_a, c / q);
    let (t0, t1) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
    if t0 < t1 {
        emit((t0, 0, t1, 0));
    }
}
