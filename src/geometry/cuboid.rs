//! The cube [lo, 1]³, lo = −1 when centred, else 0:
//! `cube(size = s | [x, y, z], center = true)` is [-1, 1]³ scaled by size/2,
//! `center = false` is [0, 1]³ scaled by size.
//!
//! The slab test; a zero direction component keeps the ray inside a slab
//! only strictly between its planes. Parts: 0/1 = −x/+x, 2/3 = −y/+y,
//! 4/5 = −z/+z.

use super::shape::RawSpan;
use super::Part;
use glam::DVec3;

/// The low corner coordinate of the cube.
pub fn low(centered: bool) -> f64 {
    if centered {
        -1.0
    } else {
        0.0
    }
}

pub fn spans(lo: f64, o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut p0, mut p1) = (0, 0);
    for axis in 0..3 {
        let (oa, da) = (o[axis], d[axis]);
        if da == 0.0 {
            if oa <= lo || oa >= 1.0 {
                return;
            }
            continue;
        }
        let (first, last) = if da > 0.0 { (lo, 1.0) } else { (1.0, lo) };
        let near = (first - oa) / da;
        let far = (last - oa) / da;
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
