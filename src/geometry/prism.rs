//! A prism: a plane region swept from z = 0 to z = 1 — OpenSCAD's
//! `linear_extrude` without twist or taper, in object space (the height is
//! the transform's). It carries its region by reference, shared by every
//! leaf made from it.
//!
//! A line meets it where its projection on the plane is inside the region
//! (the region's own line spans, [`Region::crossings`], paired even-odd)
//! and where it is inside the slab; parts: 0 the bottom cap, 1 the top cap,
//! 2 + k the side over edge k.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::plane::Region;
use glam::DVec3;
use std::sync::Arc;

const BOTTOM: Part = 0;
const TOP: Part = 1;
const SIDE: Part = 2;

#[derive(Clone, Debug, PartialEq)]
pub struct Prism {
    pub region: Arc<Region>,
}

impl Solid for Prism {
    const NAME: &'static str = "linear_extrude";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let (o, d) = (q.o, q.d);
        // The slab 0 ≤ z ≤ 1.
        let (z0, zp0, z1, zp1) = if d.z == 0.0 {
            if o.z <= 0.0 || o.z >= 1.0 {
                return;
            }
            (f64::NEG_INFINITY, BOTTOM, f64::INFINITY, TOP)
        } else {
            let (tb, tt) = (-o.z / d.z, (1.0 - o.z) / d.z);
            if tb < tt {
                (tb, BOTTOM, tt, TOP)
            } else {
                (tt, TOP, tb, BOTTOM)
            }
        };
        let (o2, d2) = (o.truncate(), d.truncate());
        if d2 == glam::DVec2::ZERO {
            // Along z: inside the slab wherever the point is in the region.
            if self.region.outlines.contains(o2) {
                emit((z0, zp0, z1, zp1));
            }
            return;
        }
        for pair in self.region.crossings(o2, d2).chunks_exact(2) {
            let ((s0, e0), (s1, e1)) = (pair[0], pair[1]);
            let (t0, p0) = if s0 > z0 { (s0, SIDE + e0) } else { (z0, zp0) };
            let (t1, p1) = if s1 < z1 { (s1, SIDE + e1) } else { (z1, zp1) };
            if t0 < t1 {
                emit((t0, p0, t1, p1));
            }
        }
    }

    fn normal(&self, _p: DVec3, part: Part) -> DVec3 {
        match part {
            BOTTOM => DVec3::NEG_Z,
            TOP => DVec3::Z,
            k => self.region.normals[(k - SIDE) as usize].extend(0.0),
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        (0.0..=1.0).contains(&p.z) && self.region.outlines.contains(p.truncate())
    }

    fn object_bounds(&self) -> Aabb {
        let r = &self.region;
        Aabb::new(r.lo.extend(0.0), r.hi.extend(1.0))
    }

    /// The farthest vertex, at the farther cap.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let flat = d.truncate();
        let v = self
            .region
            .edges
            .iter()
            .map(|(a, _)| *a)
            .max_by(|a, b| a.dot(flat).total_cmp(&b.dot(flat)))?;
        Some(v.extend(if d.z > 0.0 { 1.0 } else { 0.0 }))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![("edges", Param::Num(self.region.edges.len() as f64))]
    }

    /// POV-Ray's prism sweeps along y: turned so that it sweeps along z.
    fn pov(&self) -> String {
        let mut pts = Vec::new();
        for l in &self.region.outlines.loops {
            for p in l.iter().chain(l.first()) {
                pts.push(format!("<{:?}, {:?}>", p.x, p.y));
            }
        }
        format!(
            "prism {{ linear_sweep linear_spline 0, 1, {}, {} rotate x*90 scale <1, 1, -1>",
            pts.len(),
            pts.join(", ")
        )
    }
}
