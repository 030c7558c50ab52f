//! The exact extent of a node: its far point along a direction, where that
//! can be shown exact (OpenSCAD's `resize` measures its children by it).

use super::{Csg, NodeKind};
use crate::geometry::{Aabb, Ray};
use crate::math::boolean::Op;
use crate::stats::Stats;
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
                if *op == Op::Xor {
                    // The farthest part's far point may be covered twice.
                    return Err("the extent of an even-odd fill");
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

/// Rays a side of the grid [`Csg::tight_bounds`] casts along each axis.
pub const FRAMING_GRID: usize = 64;

impl Csg {
    /// The box of the solid itself rather than of its parts' boxes (a
    /// difference's box is its first child's; a sector cut from a ring by
    /// half-spaces has the ring's): OpenSCAD frames `--viewall` by the box
    /// of the mesh it made, which is the result's. Each side is the exact
    /// far point where [`Csg::extreme`] shows it; otherwise the tree's box
    /// found from the leaves up ([`Csg::tight`]). The node box when it is
    /// unbounded.
    pub fn tight_bounds(&self) -> Aabb {
        let Some(root) = self.root else {
            return Aabb::EMPTY;
        };
        let loose = self.bounds();
        if !loose.is_bounded() || loose.is_empty() {
            return loose;
        }
        let mut exact = [[None; 3]; 2];
        for (side, sign) in [(0, -1.0), (1, 1.0)] {
            for (axis, slot) in exact[side].iter_mut().enumerate() {
                let mut e = DVec3::ZERO;
                e[axis] = sign;
                *slot = self.extreme(root, e).ok().map(|(v, _)| sign * v);
            }
        }
        let mut out = Aabb::EMPTY;
        if exact.iter().flatten().any(Option::is_none) {
            out = self.tight(root);
        }
        for (axis, (lo, hi)) in exact[0].iter().zip(&exact[1]).enumerate() {
            if let Some(v) = lo {
                out.min[axis] = *v;
            }
            if let Some(v) = hi {
                out.max[axis] = *v;
            }
        }
        out
    }

    /// A node's box from the leaves up: a leaf's own; a union's (or an
    /// even-odd fill's) the union of its children's, leaving out a child
    /// whose node box lies inside what the larger ones already cover; an
    /// intersection's or a difference's the meet of its children's (the
    /// first one's), shrunk to the surface that rays cast through it find
    /// ([`Csg::sampled_bounds`]).
    fn tight(&self, node: u32) -> Aabb {
        let n = &self.nodes[node as usize];
        match &n.kind {
            NodeKind::Leaf(_) | NodeKind::Section(..) => n.bounds,
            NodeKind::Op(Op::Union | Op::Xor, ch) => {
                let vol = |c: &u32| {
                    let b = &self.nodes[*c as usize].bounds;
                    let e = (b.max - b.min).max(DVec3::ZERO);
                    e.x * e.y * e.z
                };
                let mut kids = ch.clone();
                kids.sort_by(|a, b| vol(b).total_cmp(&vol(a)));
                let mut acc = Aabb::EMPTY;
                for c in kids {
                    let b = self.nodes[c as usize].bounds;
                    if acc.union(&b) != acc {
                        acc = acc.union(&self.tight(c));
                    }
                }
                acc
            }
            NodeKind::Op(Op::Intersection, ch) => {
                let b = ch
                    .iter()
                    .fold(Aabb::EVERYTHING, |a, &c| a.intersect(&self.tight(c)));
                if b.is_empty() {
                    return Aabb::EMPTY;
                }
                self.refined(node, b)
            }
            NodeKind::Op(Op::Difference, ch) => self.refined(node, self.tight(ch[0])),
        }
    }

    /// The box of node `node`'s surface inside `region`: the points rays
    /// along each axis through a [`FRAMING_GRID`]² grid over the region
    /// meet, then again over their box grown by one step of that grid.
    /// The region itself when it is unbounded, or when the rays meet
    /// nothing (the solid may be thinner than a step); empty when it is.
    fn refined(&self, node: u32, region: Aabb) -> Aabb {
        if region.is_empty() || !region.is_bounded() || crate::mutant::active("framing_loose") {
            return region;
        }
        let first = self.sampled_bounds(node, &region);
        if first.is_empty() {
            return region;
        }
        let step = (region.max - region.min) / FRAMING_GRID as f64;
        let grown = Aabb::new(first.min - step, first.max + step).intersect(&region);
        first.union(&self.sampled_bounds(node, &grown))
    }

    /// The box of the surface points that rays along each axis, through
    /// the centres of a [`FRAMING_GRID`]² grid over `region`'s sides, meet.
    fn sampled_bounds(&self, node: u32, region: &Aabb) -> Aabb {
        use rayon::prelude::*;
        let n = FRAMING_GRID;
        let size = region.max - region.min;
        (0..3 * n)
            .into_par_iter()
            .map(|row| {
                let (axis, i) = (row / n, row % n);
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut dir = DVec3::ZERO;
                dir[axis] = 1.0;
                let mut st = Stats::default();
                let mut found = Aabb::EMPTY;
                for j in 0..n {
                    let mut o = region.min;
                    o[u] += size[u] * (i as f64 + 0.5) / n as f64;
                    o[v] += size[v] * (j as f64 + 0.5) / n as f64;
                    o[axis] -= 1.0 + size[axis];
                    let ray = Ray::new(o, dir);
                    self.spans_with(node, &ray, 0.0, f64::INFINITY, &mut st, |list| {
                        for s in list {
                            for t in [s.enter.t, s.exit.t] {
                                if t.is_finite() {
                                    found = found.include(o + dir * t);
                                }
                            }
                        }
                    });
                }
                found
            })
            .reduce(|| Aabb::EMPTY, |a, b| a.union(&b))
    }
}
