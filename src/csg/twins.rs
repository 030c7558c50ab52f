//! Children written twice: a union (or an intersection) of a solid with
//! itself is that solid, so a child the same as an earlier one, node for
//! node, adds nothing but work. OpenSCAD exports them as they were
//! written — a loop that places the same part at the same spot, a library
//! that adds a part each module asks for: in a survey of people's models,
//! one in five has some (a gear's teeth written four times over, 20 of a
//! belt holder's 29 cutters at one place).
//!
//! A twin's spans along any ray are its first copy's, bit for bit (the
//! same primitive, placement and material), and it meets the same rays at
//! the same points with the same normals: the picture is the same.

use super::{Csg, NodeKind};
use std::collections::HashMap;

/// How many node pairs one [`Csg::without_twins`] call compares at most
/// (past it, children are kept as they are).
const TWIN_BUDGET: usize = 100_000;
/// How deep below two children [`Csg::same_solid`] compares them (deeper
/// ones are taken to differ).
const TWIN_DEPTH: usize = 64;

impl Csg {
    /// `children` with every child that is the same solid as an earlier
    /// one left out, the rest in their order.
    pub(super) fn without_twins(&self, children: Vec<u32>) -> Vec<u32> {
        if children.len() < 2 {
            return children;
        }
        // Only children with the same box, to the bit, can be the same.
        let key = |c: u32| {
            let b = &self.nodes[c as usize].bounds;
            [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z].map(f64::to_bits)
        };
        let mut by_box: HashMap<[u64; 6], Vec<u32>> = HashMap::new();
        let mut budget = TWIN_BUDGET;
        let mut kept = Vec::with_capacity(children.len());
        for c in children {
            let earlier = by_box.entry(key(c)).or_default();
            if earlier
                .iter()
                .any(|&e| self.same_solid(e, c, &mut budget, 0))
            {
                continue;
            }
            earlier.push(c);
            kept.push(c);
        }
        kept
    }

    /// Whether nodes `a` and `b` are the same solid, node for node: equal
    /// primitives (shape, placement, material, section), the same
    /// operations over the same children in the same order. `false` once
    /// `budget` comparisons are spent, or below [`TWIN_DEPTH`] levels.
    fn same_solid(&self, a: u32, b: u32, budget: &mut usize, level: usize) -> bool {
        if a == b {
            return true;
        }
        if *budget == 0 || level >= TWIN_DEPTH {
            return false;
        }
        *budget -= 1;
        let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
        if na.bounds != nb.bounds {
            return false;
        }
        match (&na.kind, &nb.kind) {
            (NodeKind::Leaf(p), NodeKind::Leaf(q)) => {
                self.prims[*p as usize] == self.prims[*q as usize]
            }
            (NodeKind::Op(o, ca), NodeKind::Op(p, cb)) => {
                o == p
                    && ca.len() == cb.len()
                    && ca
                        .iter()
                        .zip(cb)
                        .all(|(&x, &y)| self.same_solid(x, y, budget, level + 1))
            }
            (NodeKind::Section(ca, sa), NodeKind::Section(cb, sb)) => {
                self.sections[*sa as usize] == self.sections[*sb as usize]
                    && self.same_solid(*ca, *cb, budget, level + 1)
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Csg, NodeKind, Primitive};
    use crate::geometry::{Cuboid, Shape, Sphere, Transform};
    use crate::math::boolean::Op;
    use glam::{DAffine3, DVec3};

    fn ball(csg: &mut Csg, at: DVec3, material: u32) -> u32 {
        let m = DAffine3::from_translation(at);
        csg.add_prim(Primitive::new(
            Shape::Sphere(Sphere),
            Transform::new(m).unwrap(),
            material,
        ))
    }

    fn block(csg: &mut Csg, at: DVec3) -> u32 {
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::new(2.0, 0.5, 0.5),
            Default::default(),
            at,
        );
        csg.add_prim(Primitive::new(
            Shape::Cuboid(Cuboid { centered: true }),
            Transform::new(m).unwrap(),
            0,
        ))
    }

    /// A union or an intersection leaves out a child that is an earlier
    /// one written again (a leaf, or a difference of the same leaves), and
    /// keeps one that differs in place or material; an even-odd fill keeps
    /// every child (a solid twice is nothing there). Each union contains
    /// exactly the points its children as written do.
    #[test]
    fn a_child_written_twice_is_kept_once() {
        let mut csg = Csg::default();
        let a = ball(&mut csg, DVec3::ZERO, 0);
        let again = ball(&mut csg, DVec3::ZERO, 0);
        let moved = ball(&mut csg, DVec3::new(0.5, 0.0, 0.0), 0);
        let red = ball(&mut csg, DVec3::ZERO, 1);
        let cut = |csg: &mut Csg| {
            let (s, b) = (
                ball(csg, DVec3::new(3.0, 0.0, 0.0), 0),
                block(csg, DVec3::new(3.0, 0.0, 0.0)),
            );
            csg.add_op(Op::Difference, vec![s, b])
        };
        let (d1, d2) = (cut(&mut csg), cut(&mut csg));
        let written = vec![a, again, moved, red, d1, d2];
        let u = csg.add_op(Op::Union, written.clone());
        let NodeKind::Op(_, kept) = &csg.nodes[u as usize].kind else {
            panic!("a union");
        };
        assert_eq!(kept, &vec![a, moved, red, d1]);
        let i = csg.add_op(Op::Intersection, vec![a, again, moved]);
        let NodeKind::Op(_, kept) = &csg.nodes[i as usize].kind else {
            panic!("an intersection");
        };
        assert_eq!(kept.len(), 2);
        let x = csg.add_op(Op::Xor, vec![a, again]);
        let NodeKind::Op(_, kept) = &csg.nodes[x as usize].kind else {
            panic!("a fill");
        };
        assert_eq!(kept.len(), 2);
        let mut rnd = crate::plane::tests::uniform(5);
        for _ in 0..20_000 {
            let p = DVec3::new(5.0 * rnd() - 1.5, 3.0 * rnd() - 1.5, 3.0 * rnd() - 1.5);
            let any = written.iter().any(|&c| csg.contains(c, p));
            assert_eq!(csg.contains(u, p), any, "at {p}");
        }
    }
}
