//! The unit sphere at the origin: `sphere(r = 1)`, `sphere(d = 2)`.
//!
//! Solves |o + t·d|² = 1 with the stable discriminant of Ray Tracing Gems
//! ch. 7: b² − ac = a·(1 − |o − (b/a)·d|²), which does not cancel when the
//! ray passes far from the sphere, and the roots as q/a and c/q so that
//! neither suffers cancellation.

use super::shape::RawSpan;
use glam::DVec3;

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
