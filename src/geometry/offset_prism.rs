//! The straight prism of an offset region ([`crate::plane::round_offset`]): a
//! curved outline (text) under `offset(r)` — or the round part of
//! `offset(delta)` — swept from z = 0 to 1 (the height is the transform's).
//! A line meets it where its projection on the plane is inside the offset
//! region, clipped to the slab. Parts: 0 the bottom, 1 the top, 2 + k the
//! side the boundary near edge k makes (the normal is found anew from the
//! point: away from the outline's nearest point).

use super::prism::{clip, slab};
use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::plane::round_offset::RoundOffset;
use glam::{DVec2, DVec3};
use std::sync::Arc;

const BOTTOM: Part = 0;
const TOP: Part = 1;
const SIDE: Part = 2;

#[derive(Clone, Debug, PartialEq)]
pub struct OffsetPrism {
    pub region: Arc<RoundOffset>,
    /// From z = −1/2 to 1/2 rather than 0 to 1 (OpenSCAD's `center`).
    pub centered: bool,
}

impl OffsetPrism {
    fn z_lo(&self) -> f64 {
        super::cone::bottom(self.centered)
    }
}

impl Solid for OffsetPrism {
    const NAME: &'static str = "offset";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let (o, d) = (q.o - DVec3::Z * self.z_lo(), q.d);
        let Some((z0, zp0, z1, zp1)) = slab(o, d) else {
            return;
        };
        let (o2, d2) = (o.truncate(), d.truncate());
        if d2 == DVec2::ZERO {
            if self.region.contains(o2) {
                emit((z0, zp0, z1, zp1));
            }
            return;
        }
        self.region.spans(o2, d2, |s0, e0, s1, e1| {
            clip((z0, zp0, z1, zp1), (s0, SIDE + e0, s1, SIDE + e1), emit);
        });
    }

    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        match part {
            BOTTOM => DVec3::NEG_Z,
            TOP => DVec3::Z,
            _ => self.region.normal_at(p.truncate()).extend(0.0),
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        let z = p.z - self.z_lo();
        (0.0..=1.0).contains(&z) && self.region.contains(p.truncate())
    }

    fn object_bounds(&self) -> Aabb {
        let z = self.z_lo();
        Aabb::new(self.region.lo.extend(z), self.region.hi.extend(z + 1.0))
    }

    /// A grown region's farthest point along d_xy, on whichever cap is
    /// farther; not known exactly for a shrunk one.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let q = self.region.farthest(d.truncate())?;
        let z = self.z_lo();
        Some(q.extend(if d.z > 0.0 { z + 1.0 } else { z }))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("edges", Param::Num(self.region.region.edges.len() as f64)),
            ("r", Param::Num(self.region.r)),
            ("center", Param::Bool(self.centered)),
        ]
    }

    /// POV-Ray has no offset curves: the export stops POV-Ray with the
    /// reason rather than draw something else.
    fn pov(&self) -> String {
        "#error \"csgrt: offset() of curved outlines has no POV-Ray equivalent\"\nsphere { <0, 0, 0>, 0"
            .to_string()
    }
}
