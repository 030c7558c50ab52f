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
                let local = m.matrix3.transpose() * e;
                let q = match &p.shape {
                    crate::geometry::Shape::Twisted(t) => Some(t.far_point(local)),
                    s => s.support(local),
                }
                .ok_or("the extent of a halfspace")?;
                let w = m.transform_point3(q);
                Ok((e.dot(w), w))
            }
            NodeKind::Section(..) => Err("the extent of a projection"),
            NodeKind::Op(op, ch) => {
                let mut far = Vec::with_capacity(ch.len());
                if *op == Op::Difference {
                    let first = self.extreme(ch[0], e)?;
                    // A cut whose boundary passes through the far point (a
                    // band along an outline, subtracted) contains the
                    // points just behind it.
                    let b = &self.nodes[ch[0] as usize].bounds;
                    let behind = first.1 - e * (FAR_POINT_NUDGE * (b.max - b.min).max_element());
                    if ch[1..]
                        .iter()
                        .any(|&c| self.contains(c, first.1) || self.contains(c, behind))
                    {
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

/// How far behind a difference's far point (in its first child's box's
/// largest side) [`Csg::extreme`] also asks whether a cut reaches.
const FAR_POINT_NUDGE: f64 = 1e-7;

/// Rays a side of the grid [`Csg::tight_bounds`] casts along each axis.
pub const FRAMING_GRID: usize = 64;

/// How many levels of a tree below the node framed have their own
/// surfaces sampled ([`Csg::tight`]).
pub const FRAMING_LEVELS: usize = 8;

/// Which sides of a box are asked for: `[low, high]`, per axis.
type Sides = [[bool; 3]; 2];

impl Csg {
    /// The box of the solid itself rather than of its parts' boxes (a
    /// difference's box is its first child's; a sector cut from a ring by
    /// half-spaces has the ring's): OpenSCAD frames `--viewall` by the box
    /// of the mesh it made, which is the result's. Each side is the exact
    /// far point where [`Csg::extreme`] shows it; otherwise the box found
    /// from the leaves up, each node's exact sides kept ([`Csg::tight`]).
    /// The node box when it is unbounded.
    pub fn tight_bounds(&self) -> Aabb {
        let Some(root) = self.root else {
            return Aabb::EMPTY;
        };
        let loose = self.bounds();
        if !loose.is_bounded() || loose.is_empty() {
            return loose;
        }
        // The grids' rays come in three families, along the axes: a
        // prism then tests only the edges a ray of one may cross
        // ([`Csg::viewed`]; the same spans).
        let viewed = self.viewed(None, &[DVec3::X, DVec3::Y, DVec3::Z]);
        viewed
            .as_ref()
            .unwrap_or(self)
            .tight(root, [[true; 3]; 2], 0)
    }

    /// A node's box on the sides `need` asks for (`[low, high]` per axis;
    /// the others are its node box's): each the exact far point where
    /// [`Csg::extreme`] shows it, the rest from its children
    /// ([`Csg::tight_below`]).
    fn tight(&self, node: u32, need: Sides, level: usize) -> Aabb {
        let mut out = self.nodes[node as usize].bounds;
        let mut missing = [[false; 3]; 2];
        for (side, sign) in [(0, -1.0), (1, 1.0)] {
            for axis in (0..3).filter(|&a| need[side][a]) {
                let mut e = DVec3::ZERO;
                e[axis] = sign;
                match self.extreme(node, e) {
                    Ok((v, _)) if side == 0 => out.min[axis] = -v,
                    Ok((v, _)) => out.max[axis] = v,
                    Err(_) => missing[side][axis] = true,
                }
            }
        }
        if missing.iter().flatten().any(|&m| m) {
            let below = self.tight_below(node, missing, level);
            if below.is_empty() {
                return below;
            }
            for (axis, (lo, hi)) in missing[0].iter().zip(&missing[1]).enumerate() {
                if *lo {
                    out.min[axis] = below.min[axis];
                }
                if *hi {
                    out.max[axis] = below.max[axis];
                }
            }
        }
        out
    }

    /// [`Csg::tight`] from the node's children, on the sides `need` asks
    /// for: a leaf's own box, shrunk to the surface that rays cast through
    /// it find ([`Csg::refined`]); a union's (or an even-odd fill's) the union
    /// of its children's, leaving out a child whose node box reaches no
    /// further on those sides than the larger ones already do; an
    /// intersection's or a difference's the meet of its children's (the
    /// first one's), shrunk to the surface that rays cast through it find
    /// ([`Csg::refined`]).
    fn tight_below(&self, node: u32, need: Sides, level: usize) -> Aabb {
        let n = &self.nodes[node as usize];
        // Below FRAMING_LEVELS, a node's box is left as it is: the rays
        // cast for the node above find its surface anyway, and casting
        // them at every level of a deep chain costs the depth squared.
        if level >= FRAMING_LEVELS {
            return n.bounds;
        }
        match &n.kind {
            // A leaf with no far point (a twist, an offset turned) and a
            // section: their surface inside their box.
            NodeKind::Leaf(_) | NodeKind::Section(..) => self.refined(node, n.bounds, need),
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
                    let further = (0..3).any(|a| {
                        (need[0][a] && b.min[a] < acc.min[a])
                            || (need[1][a] && b.max[a] > acc.max[a])
                    });
                    if further {
                        acc = acc.union(&self.tight(c, need, level + 1));
                    }
                }
                acc
            }
            NodeKind::Op(Op::Intersection, ch) => {
                let b = ch.iter().fold(Aabb::EVERYTHING, |a, &c| {
                    a.intersect(&self.tight(c, need, level + 1))
                });
                if b.is_empty() {
                    return Aabb::EMPTY;
                }
                self.refined(node, b, need)
            }
            NodeKind::Op(Op::Difference, ch) => {
                self.refined(node, self.tight(ch[0], need, level + 1), need)
            }
        }
    }

    /// The box of node `node`'s surface inside `region`, on the sides
    /// `need` asks for: the points that rays along each of those sides'
    /// axes, through a [`FRAMING_GRID`]² grid over the region, meet; then
    /// again over their box grown by one step of that grid. The region
    /// itself when it is unbounded, or when the rays meet nothing (the
    /// solid may be thinner than a step); empty when it is.
    fn refined(&self, node: u32, region: Aabb, need: Sides) -> Aabb {
        if region.is_empty() || !region.is_bounded() || crate::mutant::active("framing_loose") {
            return region;
        }
        let axes: Vec<usize> = (0..3).filter(|&a| need[0][a] || need[1][a]).collect();
        let first = self.sampled_bounds(node, &region, &axes);
        if first.is_empty() {
            return region;
        }
        let step = (region.max - region.min) / FRAMING_GRID as f64;
        let grown = Aabb::new(first.min - step, first.max + step).intersect(&region);
        // A second grid over a box nearly the region's own is no finer
        // (its step at least 3/4 of the first's): the first one's sides
        // stand, within a step of the first grid, 4/3 of a step of a grid
        // over their own box.
        let size = |b: &Aabb| b.max - b.min;
        if (size(&grown) - size(&region) * 0.75).min_element() >= 0.0 {
            return first;
        }
        first.union(&self.sampled_bounds(node, &grown, &axes))
    }

    /// The box of the surface points that rays along each of `axes`,
    /// through the centres of a [`FRAMING_GRID`]² grid over `region`'s
    /// sides, meet.
    fn sampled_bounds(&self, node: u32, region: &Aabb, axes: &[usize]) -> Aabb {
        use rayon::prelude::*;
        let n = FRAMING_GRID;
        let size = region.max - region.min;
        (0..axes.len() * n)
            .into_par_iter()
            .map(|row| {
                let (axis, i) = (axes[row / n], row % n);
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
                                // (Only the list's range is its solid's.)
                                if t > 0.0 && t.is_finite() {
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

#[cfg(test)]
mod tests {
    use super::super::{Csg, Primitive};
    use crate::geometry::{Aabb, Cuboid, Shape, Transform};
    use glam::{DAffine3, DVec3};

    /// A list is its solid's only over the range asked, (0, ∞) for the
    /// framing rays (a difference's later children are asked over its
    /// first's spans only, a prism over that range only): the points a
    /// ray finds before its start are not counted. A cube from −100 to 10
    /// on each axis, sampled over the box [0, 10]³ by rays that begin 11
    /// before it: each leaves by a face at 10, through the grid's centres
    /// (within the box), and enters behind its start, at −100.
    #[test]
    fn framing_rays_count_only_what_lies_ahead_of_them() {
        let mut csg = Csg::default();
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::splat(110.0),
            Default::default(),
            DVec3::splat(-100.0),
        );
        let cube = csg.add_prim(Primitive::new(
            Shape::Cuboid(Cuboid { centered: false }),
            Transform::new(m).unwrap(),
            0,
        ));
        csg.root = Some(cube);
        let region = Aabb::new(DVec3::ZERO, DVec3::splat(10.0));
        let b = csg.sampled_bounds(cube, &region, &[0, 1, 2]);
        assert!(
            (b.max - DVec3::splat(10.0)).abs().max_element() < 1e-9,
            "{b:?}"
        );
        assert!(b.min.min_element() > 0.0, "{b:?}");
    }
}
