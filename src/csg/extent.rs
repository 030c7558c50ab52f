//! The exact extent of a node: its far point along a direction, where that
//! can be shown exact (OpenSCAD's `resize` measures its children by it).

use super::{Csg, NodeKind};
use crate::math::boolean::Op;
use glam::DVec3;

impl Csg {
    /// The far point of node `node` along `e` and its value `e·p`, or why it
    /// cannot be shown exact.
    pub fn extreme(&self, node: u32, e: DVec3) -> Result<(f64, DVec3), &'static str> {
        match &self.nodes[node as usize].kind {
            NodeKind::Leaf(p) => {
                let p = &self.prims[*p as usize];
                let m = &p.xf.to_world;
                let q = p
                    .shape
                    .support(m.matrix3.transpose() * e)
                    .ok_or("the extent of a halfspace or a twisted extrusion")?;
                let w = m.transform_point3(q);
                Ok((e.dot(w), w))
            }
            NodeKind::Section(..) => Err("the extent of a projection"),
            NodeKind::Op(op, ch) => {
                let mut far = Vec::with_capacity(ch.len());
                if *op == Op::Difference {
                    let first = self.extreme(ch[0], e)?;
                    if ch[1..].iter().any(|&c| self.contains(c, first.1)) {
                        return Err("the extent of a difference that cuts its far side");
                    }
                    return Ok(first);
                }
                for &c in ch {
                    far.push(self.extreme(c, e)?);
                }
                let pick = far.iter().copied().reduce(|a, b| match (op, b.0 > a.0) {
                    (Op::Union, true) | (Op::Intersection, false) => b,
                    _ => a,
                });
                let best = pick.ok_or("the extent of nothing")?;
                if *op == Op::Intersection && !ch.iter().all(|&c| self.contains(c, best.1)) {
                    return Err("the extent of an intersection whose far point is cut away");
                }
                Ok(best)
            }
        }
    }
}
