//! The half-space z ≤ 0: `halfspace(normal = [0, 0, 1], offset = 0)` is it
//! rotated so that z points along `normal` and moved out by `offset`.
//! Unbounded: its spans have infinite ends.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part, NO_PART};
use glam::{DAffine3, DVec3};

/// The half-space z ≤ 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Halfspace;

impl Solid for Halfspace {
    const NAME: &'static str = "halfspace";

    #[inline]
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        spans(q.o, q.d, emit)
    }

    fn normal(&self, _p: DVec3, _part: Part) -> DVec3 {
        DVec3::Z
    }

    /// Its plane is flat: the normal does not depend on the point.
    fn flat_normal(&self, part: Part) -> Option<DVec3> {
        Some(self.normal(DVec3::ZERO, part))
    }

    fn contains(&self, p: DVec3) -> bool {
        p.z <= 0.0
    }

    fn object_bounds(&self) -> Aabb {
        Aabb::EVERYTHING
    }

    /// Bounded on one side when the plane is axis-aligned (a floor): the
    /// solid is n·(p − c) ≤ 0 for the world normal n.
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
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

    fn support(&self, _d: DVec3) -> Option<DVec3> {
        None
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![]
    }

    fn pov(&self) -> String {
        "plane { z, 0".to_string()
    }
}

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
