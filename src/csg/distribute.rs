//! Differences distributed over unions, for rays: `(A ∪ B ∪ …) − C` is
//! `(A − C) ∪ (B − C) ∪ …`, and a part whose box no cut's box meets is
//! left as it is. OpenSCAD models are mostly written as one: a body of
//! parts, minus a few holes or a label. A difference computes its whole
//! span list along a ray (every part the ray meets, then every cut) before
//! its first surface is known; a union at the root takes its children in
//! the order the ray enters them and stops at the first surface
//! ([`Csg::union_first`]), and its hierarchy finds each part as a leaf. A
//! union distributed into a union is flattened into it, so a tree of
//! bodies minus cuts becomes one wide union of parts (in a survey model, a
//! solar oven of 80 towers, each a union of eight parts minus a label, had
//! every ray through its crossed beams walk every tower's eight parts).
//!
//! The solid is the same; so are its spans along every ray, each boundary
//! still the surface of the primitive it was (unions and differences keep
//! boundaries, they never move them). The written tree stays the one that
//! is exported, measured and framed ([`Csg::root`]); rays walk this one
//! ([`Csg::walked`]).

use super::{Csg, NodeKind};
use crate::math::boolean::Op;

/// The most part–cut pairs whose boxes one difference compares (past it,
/// the difference is left as it is).
const PAIRS_COMPARED: usize = 1 << 20;

impl Csg {
    /// Node `n` with every difference under it distributed where that
    /// pays (see [`Csg::distribute`]): new nodes where anything changed,
    /// `n` itself where nothing did. `memo` holds each written node's
    /// answer (a node may have several parents).
    pub(super) fn distributed(&mut self, n: u32, memo: &mut Vec<Option<u32>>) -> u32 {
        if let Some(done) = memo[n as usize] {
            return done;
        }
        let out = match self.nodes[n as usize].kind.clone() {
            // A section's child is met along another line (the ray's foot):
            // left as written.
            NodeKind::Leaf(_) | NodeKind::Section(..) => n,
            NodeKind::Op(op, ch) => {
                let kids: Vec<u32> = ch.iter().map(|&c| self.distributed(c, memo)).collect();
                let spread = match (op, kids.as_slice()) {
                    (Op::Difference, &[body, cut]) => self.distribute(body, cut),
                    _ => None,
                };
                match spread {
                    Some(u) => u,
                    None if kids == ch => n,
                    None => self.add_op(op, kids),
                }
            }
        };
        memo[n as usize] = Some(out);
        out
    }

    /// `body − cut` as a union of `body`'s parts, each minus the cuts
    /// whose boxes meet its box, when `body` is a union, some part's box
    /// misses some cut's, and the parts keep no more cuts than there are
    /// parts and cuts together (a cut kept by several parts is asked by
    /// each); else `None`. The cuts are `cut`'s children if it is a union
    /// (a difference of several cuts subtracts their union: see
    /// [`Csg::add_op`]), else `cut`.
    fn distribute(&mut self, body: u32, cut: u32) -> Option<u32> {
        let NodeKind::Op(Op::Union, parts) = &self.nodes[body as usize].kind else {
            return None;
        };
        let parts = parts.clone();
        let cuts = match &self.nodes[cut as usize].kind {
            NodeKind::Op(Op::Union, ch) => ch.clone(),
            _ => vec![cut],
        };
        if parts.len().saturating_mul(cuts.len()) > PAIRS_COMPARED {
            return None;
        }
        // Closed boxes: two that touch meet (and a NaN side meets all).
        let meets = |a: u32, b: u32| {
            !(self.nodes[a as usize].bounds)
                .intersect(&self.nodes[b as usize].bounds)
                .is_empty()
        };
        let kept: Vec<Vec<u32>> = parts
            .iter()
            .map(|&p| cuts.iter().copied().filter(|&c| meets(p, c)).collect())
            .collect();
        let pairs: usize = kept.iter().map(Vec::len).sum();
        let spared = kept.iter().any(|k| k.len() < cuts.len());
        if !spared || pairs > parts.len() + cuts.len() {
            return None;
        }
        let mut out = Vec::with_capacity(parts.len());
        for (p, mut k) in parts.into_iter().zip(kept) {
            // (The mutant forgets each part's last cut.)
            if crate::mutant::active("distribute_cut_dropped") {
                k.pop();
            }
            out.push(match k.len() {
                0 => p,
                1 => self.add_op(Op::Difference, vec![p, k[0]]),
                n if n == cuts.len() => self.add_op(Op::Difference, vec![p, cut]),
                _ => {
                    let u = self.add_op(Op::Union, k);
                    self.add_op(Op::Difference, vec![p, u])
                }
            });
        }
        Some(self.add_op(Op::Union, out))
    }
}

#[cfg(test)]
mod tests {
    use crate::csg::{Csg, Op, Primitive};
    use crate::geometry::{Cuboid, Ray, Shape, Sphere, Transform};
    use crate::stats::Stats;
    use glam::{DAffine3, DQuat, DVec3};

    /// Bodies of parts minus cuts, the cuts meeting some parts and not
    /// others, as people write them: the tree rays walk is not the one
    /// written, and along random rays its spans are the written tree's,
    /// boundary for boundary (the same t, primitive, part and side); so
    /// are its first hit and its answer to a shadow ray.
    #[test]
    fn a_distributed_tree_has_the_written_spans() {
        let mut rnd = crate::plane::tests::uniform(11);
        let mut spread = 0;
        for round in 0..60 {
            let mut csg = Csg::default();
            let mut leaf = |csg: &mut Csg, size: f64| {
                let shape = if rnd() < 0.5 {
                    Shape::Cuboid(Cuboid { centered: false })
                } else {
                    Shape::Sphere(Sphere)
                };
                let axis = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
                let m = DAffine3::from_scale_rotation_translation(
                    DVec3::new(0.5 + rnd(), 0.5 + rnd(), 0.5 + rnd()) * size,
                    DQuat::from_axis_angle(axis, 3.0 * rnd()),
                    DVec3::new(20.0 * rnd(), 20.0 * rnd(), 20.0 * rnd()),
                );
                csg.add_prim(Primitive::new(shape, Transform::new(m).unwrap(), 0))
            };
            let mut bodies = Vec::new();
            for _ in 0..3 {
                let parts: Vec<u32> = (0..4).map(|_| leaf(&mut csg, 4.0)).collect();
                let body = csg.add_op(Op::Union, parts);
                let mut ch = vec![body];
                ch.extend((0..3).map(|_| leaf(&mut csg, 2.0)));
                bodies.push(csg.add_op(Op::Difference, ch));
            }
            // A difference of a difference: the outer cut is spread over
            // the inner one's parts.
            let cut = leaf(&mut csg, 3.0);
            let root = csg.add_op(Op::Difference, vec![bodies[0], cut]);
            let root = csg.add_op(Op::Union, vec![root, bodies[1], bodies[2]]);
            csg.root = Some(root);
            csg.index_unions();
            let walked = csg.walked.expect("indexed");
            if walked != root {
                spread += 1;
            }
            let mut st = Stats::default();
            let key = |s: &crate::csg::spans::Span| {
                [s.enter, s.exit].map(|b| (b.t.to_bits(), b.prim, b.part(), b.flip()))
            };
            for _ in 0..2000 {
                let o = DVec3::new(rnd(), rnd(), rnd()) * 60.0 - 20.0;
                let d = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
                let ray = Ray::new(o, d);
                let (tmin, tmax) = (0.0, f64::INFINITY);
                let written = csg.spans(root, &ray, tmin, tmax, &mut st);
                let got = csg.spans(walked, &ray, tmin, tmax, &mut st);
                let (want, got): (Vec<_>, Vec<_>) = (
                    written.iter().map(key).collect(),
                    got.iter().map(key).collect(),
                );
                assert_eq!(got, want, "round {round}: {ray:?}");
                // The first-hit query walks the distributed tree.
                let at =
                    |b: Option<crate::csg::spans::Boundary>| b.map(|b| (b.t.to_bits(), b.prim));
                let first = csg.first_boundary(&ray, tmin, tmax, &mut st);
                assert_eq!(at(first), at(crate::csg::first_surface(&written, tmin)));
                // A shadow ray's question: whether there is a boundary.
                let seen = crate::csg::first_surface(&written, tmin).is_some();
                assert_eq!(csg.occluded(&ray, tmin, tmax, &mut st), seen);
            }
        }
        assert!(spread > 30, "{spread} of 60 trees distributed");
    }
}
