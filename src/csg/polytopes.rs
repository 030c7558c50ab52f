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
use crate::geometry::polytope::{halfspace_in, pieces_across, Polytope};
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

/// Each leaf's polytopes in a cell, by node (a section is a leaf here).
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
        // A shadow's flat regions in bands across z: each meets the bands
        // of another solid at its own heights only.
        let across = columns.then_some(DVec3::Z);
        self.leaf_polytopes(node, eps, tol, &cell, across, &mut leaves)?;
        let mut out = Vec::new();
        if cell.is_empty() {
            return Ok(out);
        }
        let split = Split { tol, columns };
        self.cell_pieces(node, leaves, cell, 0, split, &mut out)?;
        Ok(out)
    }

    /// The polytopes of every leaf under `node` (a halfspace's: its part
    /// in `within`, the box of the node cut; a section's: the prisms over
    /// its solid's pieces' slices, as long as `within` along the prisms),
    /// flat regions cut across `across` ([`pieces_across`]).
    fn leaf_polytopes(
        &self,
        node: u32,
        eps: f64,
        tol: f64,
        within: &Aabb,
        across: Option<DVec3>,
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
                    _ => pieces_across(&p.shape, &p.xf.to_world, eps, tol, across)
                        .map_err(|why| format!("a `{}`: {why}", p.shape.name()))?,
                };
                out.insert(node, pieces);
                Ok(())
            }
            &NodeKind::Section(c, k) => {
                let pieces = self.section_prisms(c, k, eps, tol, within)?;
                out.insert(node, pieces);
                Ok(())
            }
            NodeKind::Op(_, ch) => ch
                .iter()
                .try_for_each(|&c| self.leaf_polytopes(c, eps, tol, within, across, out)),
        }
    }

    /// Section `k` of node `c` (its frame's plane z = 0 through the solid,
    /// swept along the frame's z) where it meets `within`: each of the
    /// solid's convex pieces (within `eps` of it) sliced exactly, the
    /// slice swept across `within`'s range of frame z.
    fn section_prisms(
        &self,
        c: u32,
        k: u32,
        eps: f64,
        tol: f64,
        within: &Aabb,
    ) -> Result<Vec<Polytope>, String> {
        let solid = self.nodes[c as usize].bounds;
        if !solid.is_bounded() {
            return Err("a projection of an unbounded solid (a halfspace)".into());
        }
        if !within.is_bounded() {
            return Err("an unbounded section (a projection not extruded)".into());
        }
        let xf = &self.sections[k as usize].xf;
        let to_object = xf.to_world.inverse();
        let level = |p: DVec3| to_object.transform_point3(p).z;
        // Frame z across `within`: f(p + z·w) = f(p) + z.
        let w = xf.to_world.matrix3 * DVec3::Z;
        let range = crate::geometry::solid::corner_box(within, &to_object);
        let (lo, hi) = (range.min.z, range.max.z);
        let mut out = Vec::new();
        for q in self.convex_pieces(c, eps, tol, false)? {
            // The fault: the solid's pieces, not their slices.
            if crate::mutant::active("section_uncut") {
                out.push(q);
                continue;
            }
            let cut = q.slice(level);
            let swept: Vec<DVec3> = cut.iter().flat_map(|&p| [p + lo * w, p + hi * w]).collect();
            out.extend(Polytope::hull(&swept, tol));
        }
        Ok(out)
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
            NodeKind::Leaf(_) | NodeKind::Section(..) => {
                local.get(&node).cloned().unwrap_or_default()
            }
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
                    acc = minus_all(&acc, &self.combine(c, local, tol)?, tol)?;
                }
                acc
            }
            // A ⊕ B = (A ∖ B) ∪ (B ∖ A), from the left.
            NodeKind::Op(Op::Xor, ch) => {
                let mut acc = self.combine(ch[0], local, tol)?;
                for &c in &ch[1..] {
                    let other = self.combine(c, local, tol)?;
                    let mut next = minus_all(&acc, &other, tol)?;
                    next.extend(minus_all(&other, &acc, tol)?);
                    limit(next.len())?;
                    acc = next;
                }
                acc
            }
        })
    }
}

/// The union of `a` less the union of `b`: each piece of `a` cut by each
/// of `b` in turn.
fn minus_all(a: &[Polytope], b: &[Polytope], tol: f64) -> Result<Vec<Polytope>, String> {
    let mut acc = a.to_vec();
    for q in b {
        acc = acc.iter().flat_map(|p| p.minus(q, tol)).collect();
        limit(acc.len())?;
    }
    Ok(acc)
}

fn limit(n: usize) -> Result<(), String> {
    if n > MAX_POLYTOPES {
        return Err(format!("more than {MAX_POLYTOPES} convex pieces"));
    }
    Ok(())
}
