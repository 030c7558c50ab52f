//! The half-space z ≤ 0: `halfspace(normal = [0, 0, 1], offset = 0)` is it
//! rotated so that z points along `normal` and moved out by `offset`.
//! Unbounded: its spans have infinite ends.

use super::shape::RawSpan;
use super::NO_PART;
use glam::DVec3;

pub fn spans(o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    if d.z == 0.0 {
        if o.z < 0.0 {
            emit((f64::NEG_INFINITY, NO_PART, f64::INFINITY, NO_PART));
        }
        return;
    }
    let t = -o.z / d.z;
    if d.z > 0.0 {
        emit((f64::NEG_INFINITY, NO_PART, t, 0));
    } else {
        emit((t, 0, f64::INFINITY, NO_PART));
    }
}
