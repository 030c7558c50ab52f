//! A node cut into convex polytopes within a distance of it: the certified
//! approximation a hull, a Minkowski sum or a shadow takes of what has no
//! exact form (an intersection, a difference, a cylinder's shadow; see
//! [`crate::geometry::polytope`]).
//!
//! Each leaf under the node becomes convex polytopes; then the node's box
//! is halved, again and again across its longest side, while one of the
//! leaves' polytopes in a cell has more than [`CELL_FACES`] faces, each
//! cell's share of every polytope cut off with it. In a cell the
//! operations are done exactly on the polytopes there: a union keeps them
//! all, an intersection meets them pairwise, a difference cuts each by the
//! subtracted one's faces (P ∖ Q for convex Q is P beyond each face of Q
//! and within the faces before it). So a finely cut sphere minus three
//! cylinders costs the faces near each other in each cell, not every
//! piece of one operand times every face of the next.

use super::{Csg, NodeKind};
use crate::geometry::polytope::{halfspace_in, pieces_of, Polytope};
use crate::geometry::Aabb;
use crate::math::boolean::Op;
use glam::DVec3;
use std::collections::HashMap;

/// The most convex pieces a node is cut into.
pub const MAX_POLYTOPES: usize = 250_000;

/// A cell is halved while one of its polytopes has more faces than this.
/// Measured (a ball cut by boxes, cones and balls in nested combinations,
/// 40×30): 64 took 42 s, 160 34 s, 400 2.0 s, 1000 1.4 s, while the
/// drilled balls of OpenSCAD's example021 took 1.0 s at 400 and 4.3 s at
/// 1000 — the cuts' cost grows with the faces a cell holds, the pieces'
/// count with the cells.
const CELL_FACES: usize = 400;

/// For a shadow, whose soup holds every upward face of every piece, the
/// smaller cells make fewer and smaller inner faces: example021 renders
/// in 5.3 s at 64 faces a cell, 34 s at 400 (800×600).
const SHADOW_CELL_FACES: usize = 64;

/// The most times a cell is halved.
const MAX_DEPTH: usize = 40;

/// How cells are halved: planes' thickness, and across z or not.
#[derive(Clone, Copy)]
struct Split {
    tol: f64,
    columns: bool,
}

/// Each leaf's polytopes in a cell, by primitive.
type Local = HashMap<u32, Vec<Polytope>>;

impl Csg {
    /// Node `node` as convex polytopes (their union) within `eps` of it,
    /// planes `tol` thick; or why not. `columns`: cells are halved across
    /// x and y only, so that no piece is cut across z (a shadow along z
    /// then sees no pieces stacked on each other).
    pub fn convex_pieces(
        &self,
        node: u32,
        eps: f64,
        tol: f64,
        columns: bool,
    ) -> Result<Vec<Polytope>, String> {
        let mut leaves = Local::new();
        let cell = self.nodes[node as usize].bounds;
        self.leaf_polytopes(node, eps, tol, &cell, &mut leaves)?;
        let mut out = Vec::new();
        if cell.is_empty() {
            return Ok(out);
        }
        let split = Split { tol, columns };
        self.cell_pieces(node, leaves, cell, 0, split, &mut out)?;
        Ok(out)
    }

    /// The polytopes of every leaf under `node` (a halfspace's: its part
    /// in `within`, the box of the node cut).
    fn leaf_polytopes(
        &self,
        node: u32,
        eps: f64,
        tol: f64,
        within: &Aabb,
        out: &mut Local,
    ) -> Result<(), String> {
        match &self.nodes[node as usize].kind {
            NodeKind::Leaf(i) => {
                let p = &self.prims[*i as usize];
                let pieces = match p.shape {
                    // Unbounded: its part in the box of the node cut.
                    crate::geometry::Shape::Halfspace(_) => {
                        halfspace_in(&p.xf.to_world, within, tol)
                            .into_iter()
                            .collect()
                    }
                    _ => pieces_of(&p.shape, &p.xf.to_world, eps, tol)
                        .ok_or_else(|| format!("a `{}`", p.shape.name()))?,
                };
                out.insert(*i, pieces);
                Ok(())
            }
            NodeKind::Section(..) => Err("a projection".into()),
            NodeKind::Op(Op::Xor, _) => Err("an even-odd fill".into()),
            NodeKind::Op(_, ch) => ch
                .iter()
                .try_for_each(|&c| self.leaf_polytopes(c, eps, tol, within, out)),
        }
    }

    /// The pieces of `node` in `cell`, whose leaves' polytopes are `local`
    /// (already cut to the cell), into `out`.
    fn cell_pieces(
        &self,
        node: u32,
        local: Local,
        cell: Aabb,
        depth: usize,
        split: Split,
        out: &mut Vec<Polytope>,
    ) -> Result<(), String> {
        let tol = split.tol;
        // The cost of cutting is in the polytopes with many faces (a finely
        // cut ball or cylinder); many small ones (an extruded outline's
        // triangles) gain nothing from halving.
        let faces = local
            .values()
            .flatten()
            .map(|p| p.faces.len())
            .max()
            .unwrap_or(0);
        let most = if split.columns {
            SHADOW_CELL_FACES
        } else {
            CELL_FACES
        };
        if faces > most && depth < MAX_DEPTH {
            let mut size = cell.max - cell.min;
            if split.columns {
                size.z = 0.0;
            }
            let axis = if size.x >= size.y.max(size.z) {
                0
            } else if size.y >= size.z {
                1
            } else {
                2
            };
            let mid = 0.5 * (cell.min[axis] + cell.max[axis]);
            let n = DVec3::AXES[axis];
            let (mut low, mut high) = (cell, cell);
            low.max[axis] = mid;
            high.min[axis] = mid;
            for (sign, half) in [(1.0, low), (-1.0, high)] {
                let part: Local = local
                    .iter()
                    .map(|(&k, ps)| {
                        let kept = ps
                            .iter()
                            .filter_map(|p| p.clip(n * sign, mid * sign, tol))
                            .collect();
                        (k, kept)
                    })
                    .collect();
                self.cell_pieces(node, part, half, depth + 1, split, out)?;
            }
            return Ok(());
        }
        out.extend(self.combine(node, &local, tol)?);
        if out.len() > MAX_POLYTOPES {
            return Err(format!("more than {MAX_POLYTOPES} convex pieces"));
        }
        Ok(())
    }

    /// Node `node` of the leaves' polytopes in `local`, exactly.
    fn combine(&self, node: u32, local: &Local, tol: f64) -> Result<Vec<Polytope>, String> {
        Ok(match &self.nodes[node as usize].kind {
            NodeKind::Leaf(i) => local.get(i).cloned().unwrap_or_default(),
            NodeKind::Op(Op::Union, ch) => {
                let mut all = Vec::new();
                for &c in ch {
                    all.extend(self.combine(c, local, tol)?);
                    limit(all.len())?;
                }
                all
            }
            NodeKind::Op(Op::Intersection, ch) => {
                let mut acc = self.combine(ch[0], local, tol)?;
                for &c in &ch[1..] {
                    let other = self.combine(c, local, tol)?;
                    let mut next = Vec::new();
                    for a in &acc {
                        for b in &other {
                            // Cut the one with more faces by the other's planes.
                            let (x, y) = if a.faces.len() >= b.faces.len() {
                                (a, b)
                            } else {
                                (b, a)
                            };
                            next.extend(x.meet(y, tol));
                        }
                        limit(next.len())?;
                    }
                    acc = next;
                }
                acc
            }
            NodeKind::Op(Op::Difference, ch) => {
                let mut acc = self.combine(ch[0], local, tol)?;
                if crate::mutant::active("pieces_uncut") {
                    // The fault: a difference's cut parts kept.
                    return Ok(acc);
                }
                for &c in &ch[1..] {
                    for b in self.combine(c, local, tol)? {
                        let mut next = Vec::new();
                        for a in &acc {
                            next.extend(a.minus(&b, tol));
                        }
                        limit(next.len())?;
                        acc = next;
                    }
                }
                acc
            }
            NodeKind::Section(..) => return Err("a projection".into()),
            NodeKind::Op(Op::Xor, _) => return Err("an even-odd fill".into()),
        })
    }
}

fn limit(n: usize) -> Result<(), String> {
    if n > MAX_POLYTOPES {
        return Err(format!("more than {MAX_POLYTOPES} convex pieces"));
    }
    Ok(())
}
