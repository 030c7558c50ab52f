//! The cube [lo, 1]³, lo = −1 when centred, else 0:
//! `cube(size = s | [x, y, z], center = true)` is [-1, 1]³ scaled by size/2,
//! `center = false` is [0, 1]³ scaled by size.
//!
//! The slab test; a zero direction component keeps the ray inside a slab
//! only strictly between its planes. Parts: 0/1 = −x/+x, 2/3 = −y/+y,
//! 4/5 = −z/+z.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use glam::DVec3;

/// The cube [-1, 1]³ when centred, else [0, 1]³.
///
/// Centring lives in the object space, not in the transform, so that a
/// part's world translation is exactly the one the file gives: a
/// `cube(0.001)` at 1e6 would otherwise sit at 1e6 + 0.0005, rounded to
/// an ulp of 1e6, which is 6e-8 of its size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    pub centered: bool,
}

impl Solid for Cuboid {
    const NAME: &'static str = "cube";

    #[inline]
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        spans(low(self.centered), q.o, q.d, emit)
    }

    fn normal(&self, _p: DVec3, part: Part) -> DVec3 {
        normal(part)
    }

    /// Every face is flat: its normal does not depend on the point.
    fn flat_normal(&self, part: Part) -> Option<DVec3> {
        Some(self.normal(DVec3::ZERO, part))
    }

    fn contains(&self, p: DVec3) -> bool {
        let lo = low(self.centered);
        p.min_element() >= lo && p.max_element() <= 1.0
    }

    fn object_bounds(&self) -> Aabb {
        Aabb::new(DVec3::splat(low(self.centered)), DVec3::ONE)
    }

    fn support(&self, d: DVec3) -> Option<DVec3> {
        let lo = low(self.centered);
        let pick = |x: f64| if x > 0.0 { 1.0 } else { lo };
        Some(DVec3::new(pick(d.x), pick(d.y), pick(d.z)))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![("centered", Param::Bool(self.centered))]
    }

    fn pov(&self) -> String {
        if self.centered {
            "box { <-1, -1, -1>, <1, 1, 1>".to_string()
        } else {
            "box { <0, 0, 0>, <1, 1, 1>".to_string()
        }
    }
}

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
