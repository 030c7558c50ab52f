//! The cube [-1, 1]³: `cube(size = s | [x, y, z], center = false)` is this
//! cube scaled by size/2 and, unless centred, moved to span [0, size].
//!
//! The slab test; a zero direction component keeps the ray inside a slab
//! only strictly between its planes. Parts: 0/1 = −x/+x, 2/3 = −y/+y,
//! 4/5 = −z/+z.

use super::shape::RawSpan;
use super::Part;
use glam::DVec3;

pub fn spans(o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut p0, mut p1) = (0, 0);
    for axis in 0..3 {
        let (oa, da) = (o[axis], d[axis]);
        if da == 0.0 {
            if oa.abs() >= 1.0 {
                return;
            }
            continue;
        }
        let near = (-da.signum() - oa) / da;
        let far = (da.signum() - oa) / da;
        let face = 2 * axis as Part;
        let (pn, pf) = if da > 0.0 {
            (face, face + 1)
        } else {
            (face + 1, face)
        };
        if near > t0 {
            t0 = near;
            p0 = pn;
        }
        if far < t1 {
            t1 = far;
            p1 = pf;
        }
    }
    if t0 < t1 {
        emit((t0, p0, t1, p1));
    }
}

pub fn normal(part: Part) -> DVec3 {
    let mut n = DVec3::ZERO;
    n[(part / 2) as usize] = if part % 2 == 0 { -1.0 } else { 1.0 };
    n
}
