//! `hull()` and `minkowski()`: convex solids known by their support
//! function ([`crate::geometry::convex`]).
//!
//! The hull of the children's union is the hull of its leaves: its support
//! is the largest of theirs, whatever their shape (a torus, a mesh: the
//! support of a solid is that of its hull). The Minkowski sum of convex
//! operands adds their supports; an operand that is a union of convex
//! parts distributes, A ⊕ (B ∪ C) = (A ⊕ B) ∪ (A ⊕ C). An intersection or a
//! difference has no such exact form: it is cut into convex polytopes
//! within `resolve::approximate::APPROXIMATION` of its size (`Csg::convex_pieces`), whose
//! hull (quickhull) or whose pieces' sums stand for it — the certified
//! approximation, noted once on stderr with its error in pixels and
//! counted by `--stats-json`. A mesh that is not convex is cut exactly
//! into the cells of its faces' planes (`geometry::mesh_cells`); one that
//! is not closed is left out there, as OpenSCAD's render leaves it out.
//! An unbounded solid (a halfspace) or one past a limit is said at the
//! statement. The children are read once, to be
//! measured, and dropped; the solid takes the statement's colour (OpenSCAD
//! shows a hull in one colour). A 2-D hull extruded straight or tapered is
//! the hull of its children's extrusions: a section of the extrusion of a
//! convex region is the region scaled, so both are the same convex solid.

use super::Resolver;
use crate::csg::{Mark, NodeKind};
use crate::error::Result;
use crate::geometry::ball_sum;
use crate::geometry::convex::{Convex, ConvexPart};
use crate::geometry::polytope::Polytope;
use crate::geometry::solid::Solid;
use crate::geometry::{Mesh, Rounded, Shape};
use crate::math::boolean::Op;
use crate::scene::Material;
use crate::syntax::ast::Statement;
use glam::{DAffine3, DVec3};

/// The most parts a hull, or a Minkowski sum's alternatives, may have.
pub const MAX_PARTS: usize = 10_000;

/// A sum of hulls.
type Sum = Vec<Vec<ConvexPart>>;

impl Resolver<'_> {
    /// The error for what a hull or sum cannot be made of: an unbounded
    /// solid, or one past a limit.
    fn not_convex(&self, s: &Statement, what: &str) -> crate::error::Error {
        self.src.error(
            s.name_span,
            format!("csgrt cannot make the `{}` of {what}", s.name),
            super::approximate::LIMITS,
        )
    }

    /// The primitives under `node`'s unions, and the other nodes there
    /// (intersections, differences, projections: cut into polytopes); for
    /// a sum (`summed`), a leaf that is not convex is cut too (a turn, a
    /// torus, a twist, a prism of a polygon that is not convex), but for a
    /// mesh, which the sum rounds as a whole or refuses; for a hull, a
    /// bounded leaf with no support point (a twist).
    fn union_members(&self, node: u32, summed: bool, leaves: &mut Vec<u32>, cut: &mut Vec<u32>) {
        match &self.b.csg.nodes[node as usize].kind {
            NodeKind::Op(Op::Union, ch) => {
                for &c in ch {
                    self.union_members(c, summed, leaves, cut);
                }
            }
            NodeKind::Leaf(i) => {
                let shape = &self.b.csg.prims[*i as usize].shape;
                let cuttable = if summed {
                    // (A mesh that is not convex: its cells, exactly.)
                    !(hulls_of(shape).is_some() || is_convex(shape))
                } else {
                    // A hull takes any bounded leaf by its support point;
                    // one with none (a twist) is cut.
                    shape.support(DVec3::X).is_none() && !matches!(shape, Shape::Halfspace(_))
                };
                if cuttable {
                    cut.push(node);
                } else {
                    leaves.push(*i);
                }
            }
            _ => cut.push(node),
        }
    }

    /// The leaves of `node`'s unions as parts placed in the world (a
    /// nested hull's own parts), and the other nodes there, or what stands
    /// in the way.
    fn parts_of(
        &self,
        node: u32,
        out: &mut Vec<ConvexPart>,
        cut: &mut Vec<u32>,
    ) -> std::result::Result<(), String> {
        let mut leaves = Vec::new();
        self.union_members(node, false, &mut leaves, cut);
        for i in leaves {
            let prim = &self.b.csg.prims[i as usize];
            if prim.shape.support(DVec3::X).is_none() {
                return Err(format!(
                    "a `{}` (unbounded, or with no support point)",
                    prim.shape.name()
                ));
            }
            match hulls_of(&prim.shape) {
                Some([one]) => out.extend(placed(one, prim.xf.to_world)),
                _ => out.push(ConvexPart {
                    shape: prim.shape.clone(),
                    to_world: prim.xf.to_world,
                }),
            }
            if out.len() > MAX_PARTS {
                return Err(format!("more than {MAX_PARTS} parts"));
            }
        }
        Ok(())
    }

    /// The alternatives (a union of them) a Minkowski operand is: each a
    /// sum of hulls.
    fn sums_of(
        &self,
        node: u32,
        cuts: &Cuts,
        out: &mut Vec<Sum>,
    ) -> std::result::Result<(), String> {
        let (mut leaves, mut cut) = (Vec::new(), Vec::new());
        self.union_members(node, true, &mut leaves, &mut cut);
        for c in cut {
            for p in cuts.get(&c).into_iter().flatten() {
                let mesh = crate::geometry::polytope::hull_mesh(&p.vertices())
                    .ok_or("a piece with no volume")?;
                out.push(vec![vec![ConvexPart {
                    shape: Shape::Mesh(mesh),
                    to_world: DAffine3::IDENTITY,
                }]]);
            }
        }
        for i in leaves {
            let prim = &self.b.csg.prims[i as usize];
            let m = prim.xf.to_world;
            match hulls_of(&prim.shape) {
                Some(hulls) => out.push(hulls.iter().map(|h| placed(h, m).collect()).collect()),
                None if is_convex(&prim.shape) => out.push(vec![vec![ConvexPart {
                    shape: prim.shape.clone(),
                    to_world: m,
                }]]),
                None => return Err(format!("a non-convex `{}`", prim.shape.name())),
            }
        }
        Ok(())
    }

    /// One convex leaf of the sum of `hulls` (read in the statement's own
    /// frame), placed by `frame`. Far from that frame's origin — its
    /// centre farther out than its size — the set is moved to be centred
    /// there, so that its own coordinates carry the precision of its size;
    /// otherwise the parts keep the file's own placement, and the leaf the
    /// statement's transform, rounded no more than any primitive's.
    fn convex_leaf(
        &mut self,
        s: &Statement,
        hulls: Sum,
        frame: DAffine3,
        mat: Material,
        covered: &dyn Fn(&[DVec3]) -> bool,
    ) -> Result<Option<u32>> {
        // A hull or a sum of polytopes: the polytope, written out.
        if let Some(mesh) = crate::geometry::convex::polytope_sum(&hulls) {
            return self.leaf(s, Shape::Mesh(mesh), frame, mat);
        }
        // A hull of frustums on one axis: the turn of its profile, which
        // keeps its parts for a hull it is a part of.
        if let Some((lathe, place)) = crate::geometry::coaxial::as_lathe(&hulls) {
            let parts = vec![(Shape::Lathe(lathe), place)];
            return self.rounded_leaf(s, parts, hulls, frame, mat);
        }
        // Such a hull plus a ball: turned too.
        if let Some(pieces) = crate::geometry::coaxial::as_rounded_lathe(&hulls) {
            return self.rounded_leaf(s, pieces.parts, hulls, frame, mat);
        }
        // A polytope rounded by a ball: written out as exact primitives.
        let rounded = ball_sum::as_rounded(&hulls)
            .and_then(|(pts, r)| ball_sum::pieces_beside(&pts, r, covered))
            .or_else(|| ball_sum::as_ball_chain(&hulls))
            .or_else(|| ball_sum::as_cylinders(&hulls))
            .or_else(|| crate::geometry::disc_sum::as_disc_sum(&hulls))
            .or_else(|| crate::geometry::disc_hull::as_disc_hull(&hulls));
        if let Some(pieces) = rounded.filter(|_| !crate::mutant::active("hull_gjk_normals")) {
            return self.rounded_leaf(s, pieces.parts, hulls, frame, mat);
        }
        let c = Convex::new(hulls);
        let b = c.object_bounds();
        let centre = b.center();
        let (c, world) = if centre.abs().max_element() > (b.max - b.min).max_element() {
            let (c, centre) = Convex::centred(c.hulls);
            (c, frame * DAffine3::from_translation(centre))
        } else {
            (c, frame)
        };
        self.leaf(s, Shape::Convex(c), world, mat)
    }

    /// The hull of the leaves already read into `node` (then dropped), in
    /// the frame that `frame` places.
    pub(super) fn hull_of(
        &mut self,
        s: &Statement,
        node: u32,
        mark: Mark,
        frame: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let (mut parts, mut cut) = (Vec::new(), Vec::new());
        let noted = self.b.approximations.len();
        let found = self
            .parts_of(node, &mut parts, &mut cut)
            .and_then(|()| self.polytopes(s, &cut, frame, false));
        let eps = self.cut_within(&cut);
        self.b.csg.rewind(mark);
        let polytopes = found.map_err(|why| self.not_convex(s, &why))?;
        if !cut.is_empty() {
            // The cut nodes' part: the hull of their polytopes' corners;
            // the hull being approximated anyway, with the other parts'
            // polytopes too, where they can be cut.
            let mut pts: Vec<DVec3> = polytopes.iter().flat_map(|p| p.vertices()).collect();
            if !parts.is_empty() {
                if let Some(more) = self.part_polytopes(&parts, eps, frame, noted) {
                    pts.extend(more);
                    parts.clear();
                }
            }
            match crate::geometry::polytope::hull_mesh(&pts) {
                Some(mesh) if parts.is_empty() => {
                    return self.leaf(s, Shape::Mesh(mesh), frame, mat);
                }
                Some(mesh) => parts.push(ConvexPart {
                    shape: Shape::Mesh(mesh),
                    to_world: DAffine3::IDENTITY,
                }),
                None if parts.is_empty() => return Ok(None),
                None => {}
            }
        }
        self.convex_leaf(s, vec![parts], frame, mat, &|_| false)
    }

    /// 3-D `hull()` of its children.
    pub(super) fn hull(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        if super::resize::is_planar(s) {
            return self.slab(s, xf, mat);
        }
        crate::scene::args::Args::bind(self.src, s, &[])?;
        // The children in the statement's own frame: the leaf carries xf.
        let mark = self.b.csg.mark();
        let noted = self.b.approximations.len();
        let ids = self.children(s, DAffine3::IDENTITY, mat, depth)?;
        self.placed_approximations(noted, &xf);
        let Some(node) = self.union(ids) else {
            return Ok(None);
        };
        self.hull_of(s, node, mark, xf, mat)
    }

    /// 3-D `minkowski(convexity)` of its children.
    pub(super) fn minkowski(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        if super::resize::is_planar(s) {
            return self.slab(s, xf, mat);
        }
        crate::scene::args::Args::bind(self.src, s, &["convexity"])?;
        // The operands in the statement's own frame (the sum moves once,
        // with the leaf's transform), each a union of primitives.
        let mark = self.b.csg.mark();
        let noted = self.b.approximations.len();
        let mut nodes = Vec::new();
        for c in s.children.iter().filter(|c| !super::skipped(c)) {
            // The fault: each later operand moved by the statement's
            // translation too.
            let at = if crate::mutant::active("minkowski_moved_twice") && !nodes.is_empty() {
                DAffine3::from_translation(xf.translation)
            } else {
                DAffine3::IDENTITY
            };
            nodes.extend(self.statement(c, at, mat, depth + 1)?);
        }
        self.placed_approximations(noted, &xf);
        // The operand taken whole (a mesh summed as it is) is not cut.
        let ops = self.summands(&nodes);
        let cut: Vec<u32> = nodes
            .iter()
            .copied()
            .filter(|&n| Some(n) != ops.whole())
            .collect();
        let read = self
            .cut_operands(s, &cut, xf)
            .and_then(|cuts| self.sum_of(&nodes, ops, &cuts));
        self.b.csg.rewind(mark);
        match read.map_err(|why| self.not_convex(s, &why))? {
            Summed::Mesh(mesh, to, r) => {
                let pieces = ball_sum::mesh_rounded(&mesh, to, r);
                let limit = ball_sum::MAX_ROUNDED_TRIANGLES;
                self.pieces_leaf(
                    s,
                    pieces,
                    &format!("a mesh of more than {limit} triangles"),
                    xf,
                    mat,
                )
            }
            Summed::MeshPlus(mesh, to, rest) => {
                let pieces = ball_sum::mesh_plus(&mesh, to, &rest);
                let limit = ball_sum::MAX_SUMMED_TRIANGLES;
                let what = format!(
                    "a mesh of more than {limit} triangles plus a convex solid other than a ball"
                );
                self.pieces_leaf(s, pieces, &what, xf, mat)
            }
            Summed::Convex(combos) => {
                let combos: Vec<Sum> = combos.into_iter().filter(|c| !c.is_empty()).collect();
                // Polytopes summed with one ball: the pieces of each sum
                // that lie in an earlier one's are left out.
                let rounded: Vec<_> = combos.iter().map(|c| ball_sum::as_rounded(c)).collect();
                let radius = rounded.iter().flatten().map(|x| x.1).next();
                let corners: Vec<Option<&[DVec3]>> = rounded
                    .iter()
                    .map(|x| x.as_ref().filter(|x| Some(x.1) == radius).map(|x| &x.0[..]))
                    .collect();
                let cells = ball_sum::Cells::new(&corners);
                let mut leaves = Vec::new();
                for (k, sum) in combos.into_iter().enumerate() {
                    let covered =
                        |pts: &[DVec3]| corners[k].is_some() && cells.earlier_holds(k, pts);
                    leaves.push(self.convex_leaf(s, sum, xf, mat, &covered)?);
                }
                Ok(self.op(Op::Union, leaves))
            }
        }
    }

    /// One leaf of a sum written out as pieces; `None` (too many) refused
    /// as `what`.
    fn pieces_leaf(
        &mut self,
        s: &Statement,
        pieces: Option<ball_sum::Pieces>,
        what: &str,
        xf: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let Some(pieces) = pieces else {
            return Err(self.not_convex(s, what));
        };
        self.rounded_leaf(s, pieces.parts, Vec::new(), xf, mat)
    }

    /// A leaf of the union of exact `parts` (keeping the `hulls` they are
    /// of, for a hull they are part of), placed by `frame`.
    fn rounded_leaf(
        &mut self,
        s: &Statement,
        parts: Vec<(Shape, DAffine3)>,
        hulls: Sum,
        frame: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let shape = Rounded::new(parts, hulls).map_err(|_| {
            self.src.error(
                s.name_span,
                format!("this `{}` is out of range or flattened", s.name),
                "expected parts of a size within 1e-15 to 1e15 of their distances",
            )
        })?;
        self.leaf(s, Shape::Rounded(shape), frame, mat)
    }

    /// What the operands `nodes` are made of: balls, one mesh that is not
    /// convex, and whether there are others.
    fn summands(&self, nodes: &[u32]) -> Operands {
        let mut ops = Operands {
            mesh: None,
            centre: DVec3::ZERO,
            r: 0.0,
            others: false,
        };
        for &node in nodes {
            let (mut leaves, mut cut) = (Vec::new(), Vec::new());
            self.union_members(node, false, &mut leaves, &mut cut);
            if !cut.is_empty() || leaves.is_empty() {
                ops.others = true;
                continue;
            }
            let prim = &self.b.csg.prims[leaves[0] as usize];
            let part = ConvexPart {
                shape: prim.shape.clone(),
                to_world: prim.xf.to_world,
            };
            match (&part.shape, ball_sum::ball(&part)) {
                (_, Some((c, radius))) if leaves.len() == 1 => {
                    ops.centre += c;
                    ops.r += radius;
                }
                (Shape::Mesh(m), None)
                    if leaves.len() == 1 && ops.mesh.is_none() && !is_convex(&part.shape) =>
                {
                    ops.mesh = Some((m.clone(), part.to_world, node));
                }
                _ => ops.others = true,
            }
        }
        ops
    }

    /// What the operands `nodes` (made of `ops`) sum to: one mesh that is
    /// not convex and balls (the mesh rounded by their sum), or a mesh
    /// plus the others, or else every choice of one convex piece from each
    /// operand's union, or what stands in the way.
    fn sum_of(
        &self,
        nodes: &[u32],
        ops: Operands,
        cuts: &Cuts,
    ) -> std::result::Result<Summed, String> {
        match ops.mesh {
            Some((m, to, _)) if !ops.others && ops.r > 0.0 => Ok(Summed::Mesh(
                m,
                DAffine3::from_translation(ops.centre) * to,
                ops.r,
            )),
            Some((m, to, mesh_node)) if ops.others => {
                // The mesh plus the sum of the others, distributed over
                // their unions: one convex set for each choice of a piece
                // of each.
                let others: Vec<u32> = nodes.iter().copied().filter(|&n| n != mesh_node).collect();
                Ok(Summed::MeshPlus(m, to, self.choices(&others, cuts)?))
            }
            _ => Ok(Summed::Convex(self.choices(nodes, cuts)?)),
        }
    }

    /// The polytopes of the intersections and differences among the
    /// operands `nodes` (see [`Resolver::polytopes`]), by node.
    fn cut_operands(
        &mut self,
        s: &Statement,
        nodes: &[u32],
        frame: DAffine3,
    ) -> std::result::Result<Cuts, String> {
        let mut cuts = Cuts::new();
        for &node in nodes {
            let (mut leaves, mut cut) = (Vec::new(), Vec::new());
            self.union_members(node, true, &mut leaves, &mut cut);
            for c in cut {
                let mut pieces = self.polytopes(s, &[c], frame, false)?;
                // A convex node (an intersection of convex solids) is the
                // hull of its pieces, within the same distance (that
                // distance's neighbourhood of a convex set is convex): one
                // convex part to sum, not each of its cells.
                if pieces.len() > 1 && self.convex_node(c) {
                    let pts: Vec<DVec3> = pieces.iter().flat_map(|p| p.vertices()).collect();
                    let b = self.b.csg.nodes[c as usize].bounds;
                    let tol = crate::geometry::polytope::plane_tolerance(&b);
                    pieces = Polytope::hull(&pts, tol).into_iter().collect();
                }
                cuts.insert(c, pieces);
            }
        }
        Ok(cuts)
    }

    /// Whether node `node` is convex: a convex leaf, or an intersection of
    /// convex nodes.
    fn convex_node(&self, node: u32) -> bool {
        match &self.b.csg.nodes[node as usize].kind {
            NodeKind::Leaf(i) => is_convex(&self.b.csg.prims[*i as usize].shape),
            NodeKind::Op(Op::Intersection, ch) => ch.iter().all(|&c| self.convex_node(c)),
            _ => false,
        }
    }

    /// Every choice of one convex piece from each operand's union, summed.
    fn choices(&self, nodes: &[u32], cuts: &Cuts) -> std::result::Result<Vec<Sum>, String> {
        let mut combos: Vec<Sum> = vec![Vec::new()];
        for &node in nodes {
            let mut alts = Vec::new();
            self.sums_of(node, cuts, &mut alts)?;
            if alts.is_empty() {
                // An operand that is empty (an intersection of parts that
                // do not meet): left out, as OpenSCAD leaves out an empty
                // child of minkowski().
                continue;
            }
            let mut next = Vec::new();
            for c in &combos {
                for a in &alts {
                    let mut sum = c.clone();
                    sum.extend(a.iter().cloned());
                    next.push(sum);
                }
            }
            if next.len() > MAX_PARTS {
                return Err(format!("more than {MAX_PARTS} convex pieces"));
            }
            combos = next;
        }
        Ok(combos)
    }
}

/// The convex polytopes of the operands' intersections and differences, by
/// node.
type Cuts = std::collections::HashMap<u32, Vec<Polytope>>;

/// A `minkowski()`'s operands: a mesh that is not convex (placed, and its
/// node), the balls' summed centre and radius, and whether there are
/// others.
struct Operands {
    mesh: Option<(Mesh, DAffine3, u32)>,
    centre: DVec3,
    r: f64,
    others: bool,
}

impl Operands {
    /// The operand summed whole, not cut into polytopes: the mesh, if it
    /// is rounded by the balls or added to the others.
    fn whole(&self) -> Option<u32> {
        self.mesh
            .as_ref()
            .filter(|_| self.others || self.r > 0.0)
            .map(|m| m.2)
    }
}

/// What a `minkowski()` sums to.
enum Summed {
    /// A mesh (placed) rounded by a ball of this radius.
    Mesh(Mesh, DAffine3, f64),
    /// A mesh (placed) plus the union of these convex sets (sums of hulls).
    MeshPlus(Mesh, DAffine3, Vec<Sum>),
    /// The union of these convex sums.
    Convex(Vec<Sum>),
}

/// The hulls a hull or sum already made is the sum of.
fn hulls_of(shape: &Shape) -> Option<&[Vec<ConvexPart>]> {
    match shape {
        Shape::Convex(Convex { hulls, .. }) => Some(hulls),
        Shape::Rounded(Rounded { hulls, .. }) if !hulls.is_empty() => Some(hulls),
        _ => None,
    }
}

/// Parts placed once more, by `m`.
fn placed(parts: &[ConvexPart], m: DAffine3) -> impl Iterator<Item = ConvexPart> + '_ {
    parts.iter().map(move |p| ConvexPart {
        shape: p.shape.clone(),
        to_world: m * p.to_world,
    })
}

/// Whether a solid is convex (so that Minkowski sums with it add supports).
fn is_convex(shape: &Shape) -> bool {
    match shape {
        Shape::Sphere(_) | Shape::Cuboid(_) | Shape::Cone(_) | Shape::Convex(_) => true,
        Shape::Rounded(r) => !r.hulls.is_empty(),
        Shape::Prism(p) => {
            let o = &p.region.outlines;
            o.loops.len() == 1 && !o.curved() && crate::plane::hull::convex_polygon(&o.loops[0])
        }
        Shape::Mesh(m) => {
            let d = &m.data;
            d.verts.len() * d.tris.len() <= 10_000_000
                && d.tris.iter().all(|t| {
                    let [a, b, c] = t.map(|i| d.verts[i as usize]);
                    let n = (b - a).cross(c - a);
                    let side = |p: DVec3| n.dot(p - a);
                    let scale = n.length() * (b - a).length().max((c - a).length()) * 1e-12;
                    let (lo, hi) = d.verts.iter().fold((0.0f64, 0.0f64), |(l, h), &p| {
                        let v = side(p);
                        (l.min(v), h.max(v))
                    });
                    lo >= -scale || hi <= scale
                })
        }
        _ => false,
    }
}
