//! The CSG tree and the queries every node answers: its bounds, its spans
//! along a ray, the first surface a ray hits, and point membership.
//!
//! As slides 38–40 of the seed lecture: leaves return their entry/exit
//! lists, each node combines its children's lists from the leaves to the
//! root, and a difference flips the normals of the surfaces it takes from
//! its subtracted children. The normal and material are looked up only for
//! the boundary that wins ([`Csg::surface`]).

mod distribute;
mod extent;
mod polytopes;
mod twins;
pub use polytopes::MAX_POLYTOPES;
pub mod spans;

use crate::geometry::aabb::AabbLanes;
use crate::geometry::bvh::Bvh;
use crate::geometry::{Aabb, Need, Probe, Ray, Shape, Transform};
use crate::math::boolean::Op;
use crate::math::robust::coincidence;
use crate::plane::pencil::Pencil;
use crate::stats::Stats;
use glam::DVec3;
use smallvec::SmallVec;
use spans::{Boundary, Quick, Span};

/// A primitive placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    pub shape: Shape,
    pub xf: Transform,
    /// Index into the scene's materials.
    pub material: u32,
    /// World bounding box ([`Aabb::EVERYTHING`] if unbounded).
    pub bounds: Aabb,
    /// The innermost [`Section`] the primitive lies in, if any: its
    /// surface is then met along the ray projected into that section's
    /// plane (and so on outwards).
    pub section: Option<u32>,
    /// The unit world normals of a solid whose parts 0 to 5 are each flat
    /// ([`Shape::flat_normal`]: a box's six faces, a half-space's one
    /// plane), found once as [`Csg::surface`] would find them at each hit.
    faces: Option<[DVec3; 6]>,
}

impl Primitive {
    pub fn new(shape: Shape, xf: Transform, material: u32) -> Primitive {
        let bounds = shape.world_bounds(&xf.to_world);
        let flat = [0, 1, 2, 3, 4, 5].map(|k| shape.flat_normal(k));
        let faces = flat
            .iter()
            .all(Option::is_some)
            .then(|| flat.map(|n| xf.normal_to_world(n.expect("every part is flat"))));
        Primitive {
            shape,
            xf,
            material,
            bounds,
            section: None,
            faces,
        }
    }
}

/// `projection(cut = true)` extruded: the solid of the points whose foot
/// in the plane z = 0 of `xf`'s frame lies in the child. A ray crosses it
/// exactly where the ray's own foot — the line projected along the
/// frame's z into that plane, with the same parameter t — crosses the
/// child, so the child's spans along that line are the section's, and the
/// normal there is the child's with its z part (in the frame) removed.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    pub xf: Transform,
    /// The section this one lies in, if any.
    pub outer: Option<u32>,
}

impl Section {
    /// The foot of `ray` in the plane: `None` for a ray along the frame's
    /// z, whose foot is one point.
    pub fn project(&self, ray: &Ray) -> Option<Ray> {
        let (o, d) = self.xf.ray_to_object(ray);
        if d.x == 0.0 && d.y == 0.0 {
            return None;
        }
        let m = &self.xf.to_world;
        Some(Ray::new(
            m.transform_point3(DVec3::new(o.x, o.y, 0.0)),
            m.matrix3 * DVec3::new(d.x, d.y, 0.0),
        ))
    }

    /// The foot of a world point in the plane.
    pub fn foot(&self, p: DVec3) -> DVec3 {
        let q = self.xf.point_to_object(p);
        self.xf.to_world.transform_point3(DVec3::new(q.x, q.y, 0.0))
    }

    /// The section's normal where the child's unit world normal is `n`:
    /// in the frame, the child's normal less its z part.
    pub fn normal(&self, n: DVec3) -> DVec3 {
        if crate::mutant::active("section_unflattened") {
            return n;
        }
        let mut local = self.xf.to_world.matrix3.transpose() * n;
        local.z = 0.0;
        let w = self.xf.normal * local;
        if w == DVec3::ZERO {
            n
        } else {
            w.normalize()
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    Leaf(u32),
    /// An operation over two or more children; a difference is the first
    /// child minus the rest.
    Op(Op, Vec<u32>),
    /// The child (a node) seen through [`Csg::sections`]`[k]`: unbounded
    /// along the section's z, so it stands under an intersection.
    Section(u32, u32),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub kind: NodeKind,
    /// World box: the union of a union's children, the overlap of an
    /// intersection's, a difference's first child's.
    pub bounds: Aabb,
    /// For a union of many children: a hierarchy over the bounded ones.
    pub index: Option<Box<UnionIndex>>,
    /// For a union of [`LANES_MIN`] children or more whose first-hit query
    /// sorts them (not one that walks its hierarchy): their boxes (cut to
    /// where the union matters), four a group in the children's order,
    /// tested four at once (empty for other nodes); a child whose box is
    /// cut to nothing is left out (an empty box's slab test would read
    /// its sides swapped).
    pub lanes: Vec<AabbLanes<4>>,
    /// The children the lanes hold, in order.
    pub lane_ids: Vec<u32>,
    /// Whether a query whose root this is tests its box before the query
    /// is set up (`Csg::root_box`): a bounded box (an empty one counts,
    /// and culls) of a node that is not a union walking its hierarchy.
    /// Set by `Csg::add_node`.
    pub pretest: bool,
}

/// From how many children a union's boxes are kept four to a group (fewer
/// are tested one by one).
pub const LANES_MIN: usize = 4;

/// A union gets a hierarchy over its children from this many bounded ones.
pub const UNION_INDEX_MIN: usize = 8;
/// Children a leaf of a union's hierarchy holds: two, tested together.
pub const UNION_LEAF: usize = 2;

/// How a wide union finds the children a ray may meet.
#[derive(Clone, Debug, PartialEq)]
pub struct UnionIndex {
    pub bvh: Bvh,
    /// Whether a first-hit query walks the hierarchy, nearer subtrees
    /// first, rather than sorting every child whose box the ray meets.
    pub near_first: bool,
    /// Children without a finite box (halfspaces), always looked at.
    pub unbounded: Vec<u32>,
    /// Whether a child is held by several boxes ([`Csg::pieces`]): a walk
    /// may then reach it more than once, and asks it once.
    pub split: bool,
}

/// A CSG tree over its primitives. Node ids index `nodes`; children come
/// before their parents.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Csg {
    pub prims: Vec<Primitive>,
    pub nodes: Vec<Node>,
    pub sections: Vec<Section>,
    /// The tree as the file wrote it: what is exported, measured and
    /// framed.
    pub root: Option<u32>,
    /// The same solid as rays walk it ([`Csg::index_unions`] sets it; the
    /// written root until then): each difference of a union distributed
    /// over the union's children where its cuts meet only some of them
    /// (`csg/distribute.rs`).
    pub walked: Option<u32>,
}

/// A surface point found by a query, with its unit outward normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    pub t: f64,
    pub point: DVec3,
    pub normal: DVec3,
    pub prim: u32,
}

/// How far a tree was built, to go back to once nodes read only to be
/// measured (a hull's, a resize's, a projection's children) are done with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mark {
    prims: usize,
    nodes: usize,
    sections: usize,
}

impl Csg {
    /// Where the tree stands now.
    pub fn mark(&self) -> Mark {
        Mark {
            prims: self.prims.len(),
            nodes: self.nodes.len(),
            sections: self.sections.len(),
        }
    }

    /// Everything added since `mark` dropped.
    pub fn rewind(&mut self, mark: Mark) {
        self.prims.truncate(mark.prims);
        self.nodes.truncate(mark.nodes);
        self.sections.truncate(mark.sections);
    }

    /// A copy whose straight prisms know the line families a render's rays
    /// meet their regions along — through the camera's `eye` (a
    /// perspective camera's rays), along each of `dirs` (a directional
    /// light's shadow rays, an orthographic camera's rays) — so that a
    /// ray of one tests only the edges it may cross ([`Pencil`]): the
    /// same answers. Each family is taken into the prism's space as a
    /// ray's origin and direction are ([`Transform::ray_to_object`]'s
    /// two halves), so a ray of it matches to the bit.
    /// `None` when no prism gets one (nothing to copy).
    pub fn viewed(&self, eye: Option<DVec3>, dirs: &[DVec3]) -> Option<Csg> {
        use rayon::prelude::*;
        // Each prism's families on its own, on every thread (a text of
        // hundreds of glyphs took a few milliseconds on one).
        let views: Vec<(usize, Vec<Pencil>)> = self
            .prims
            .par_iter()
            .enumerate()
            .filter_map(|(i, p)| {
                let Shape::Prism(prism) = &p.shape else {
                    return None;
                };
                // A tapered prism's lines are not the rays' projections; a
                // primitive in a section is met along the ray's foot.
                if prism.top != 1.0 || p.section.is_some() {
                    return None;
                }
                let mut views = Vec::new();
                if let Some(e) = eye {
                    let o = p.xf.point_to_object(e).truncate();
                    views.extend(Pencil::through(&prism.region, o));
                }
                for &d in dirs {
                    let od = p.xf.dir_to_object(d).truncate();
                    views.extend(Pencil::along(&prism.region, od));
                }
                (!views.is_empty()).then_some((i, views))
            })
            .collect();
        if views.is_empty() {
            return None;
        }
        let mut copy = self.clone();
        for (i, v) in views {
            if let Shape::Prism(q) = &mut copy.prims[i].shape {
                q.views = v;
            }
        }
        Some(copy)
    }

    pub fn add_prim(&mut self, prim: Primitive) -> u32 {
        let bounds = prim.bounds;
        self.prims.push(prim);
        let id = self.prims.len() as u32 - 1;
        self.add_node(Node {
            kind: NodeKind::Leaf(id),
            bounds,
            index: None,
            lanes: Vec::new(),
            lane_ids: Vec::new(),
            pretest: false,
        })
    }

    /// Adds an operation node over `children`, with its bounds derived. A
    /// difference of several subtracted children becomes the first minus
    /// the union of the rest, so that a wide one is indexed like a union.
    pub fn add_op(&mut self, op: Op, mut children: Vec<u32>) -> u32 {
        if op == Op::Union {
            // Unions of unions are one union: flatter trees stop earlier.
            children = children
                .into_iter()
                .flat_map(|c| match &self.nodes[c as usize].kind {
                    NodeKind::Op(Op::Union, ch) => ch.clone(),
                    _ => vec![c],
                })
                .collect();
        }
        if matches!(op, Op::Union | Op::Intersection) {
            children = self.without_twins(children);
        }
        if op == Op::Intersection {
            // Later children are asked only where the earlier ones leave
            // something: the cheaper first lets a small part cut a large
            // one's query short (a bevel gear: one cone intersected with a
            // union of a cone and 205 teeth). Cheaper: fewer leaves by a
            // power of four (1–3, 4–15, 16–63, …); within one such class
            // the file's order.
            children.sort_by_cached_key(|&c| self.leaf_count(c, LEAF_COUNT_CAP).ilog(4));
        }
        if op == Op::Difference && children.len() > 2 {
            let rest = children.split_off(1);
            let u = self.add_op(Op::Union, rest);
            children.push(u);
        }
        let bounds = op_bounds(op, children.iter().map(|&c| self.nodes[c as usize].bounds));
        // A union's hierarchy waits for `index_unions`: one made here and
        // then flattened into its parent (a chain of nested unions) would
        // be built again at every level.
        self.add_node(Node {
            kind: NodeKind::Op(op, children),
            bounds,
            index: None,
            lanes: Vec::new(),
            lane_ids: Vec::new(),
            pretest: false,
        })
    }

    /// How many leaves node `node` has, counted up to `cap`.
    fn leaf_count(&self, node: u32, cap: usize) -> usize {
        match &self.nodes[node as usize].kind {
            NodeKind::Leaf(_) => 1,
            NodeKind::Section(c, _) => self.leaf_count(*c, cap),
            NodeKind::Op(_, ch) => {
                let mut n = 0;
                for &c in ch {
                    n += self.leaf_count(c, cap - n);
                    if n >= cap {
                        return cap;
                    }
                }
                n
            }
        }
    }

    /// Adds the section of node `child` (built with its primitives placed
    /// in the frame of `xf`): the primitives and sections added since
    /// `first_prim` and `first_section` that lie in no section yet now
    /// lie in this one. Unbounded: see [`NodeKind::Section`].
    pub fn add_section(
        &mut self,
        child: u32,
        xf: Transform,
        first_prim: usize,
        first_section: usize,
    ) -> u32 {
        let k = self.sections.len() as u32;
        for p in &mut self.prims[first_prim..] {
            p.section.get_or_insert(k);
        }
        for s in &mut self.sections[first_section..] {
            s.outer.get_or_insert(k);
        }
        self.sections.push(Section { xf, outer: None });
        self.add_node(Node {
            kind: NodeKind::Section(child, k),
            bounds: Aabb::EVERYTHING,
            index: None,
            lanes: Vec::new(),
            lane_ids: Vec::new(),
            pretest: false,
        })
    }

    /// The box of `node` with every primitive moved by `m` first (the same
    /// rules as the nodes' own boxes; a section is unbounded).
    pub fn bounds_in(&self, node: u32, m: &glam::DAffine3) -> Aabb {
        match &self.nodes[node as usize].kind {
            NodeKind::Leaf(p) => {
                let p = &self.prims[*p as usize];
                p.shape.world_bounds(&(*m * p.xf.to_world))
            }
            NodeKind::Section(..) => Aabb::EVERYTHING,
            NodeKind::Op(op, ch) => op_bounds(*op, ch.iter().map(|&c| self.bounds_in(c, m))),
        }
    }

    /// Once the tree is whole: sets [`Csg::walked`], the tree rays walk
    /// (its differences distributed: `csg/distribute.rs`), and builds the
    /// hierarchy (and the boxes in lanes, where the sorting first-hit query
    /// reads them: a union that walks its hierarchy does not) of every
    /// union under either root; the nodes' pretests after them. The
    /// children's boxes there are cut to where the union can matter
    /// ([`Csg::contexts`]), so the hierarchy and the lanes answer for
    /// queries of a whole tree (from its root), as every query is.
    pub fn index_unions(&mut self) {
        let Some(root) = self.root else {
            return;
        };
        let mut memo = vec![None; self.nodes.len()];
        let walked = self.distributed(root, &mut memo);
        self.walked = Some(walked);
        // The written tree keeps its hierarchies too: the framing box
        // casts rays through it ([`Csg::tight_bounds`]).
        let ctx = self.contexts(&[root, walked]);
        let mut todo = vec![root, walked];
        let mut seen = vec![false; self.nodes.len()];
        while let Some(n) = todo.pop() {
            if std::mem::replace(&mut seen[n as usize], true) {
                continue;
            }
            match &self.nodes[n as usize].kind {
                NodeKind::Op(op, ch) => {
                    todo.extend(ch.iter().copied());
                    if *op == Op::Union {
                        let ch = ch.clone();
                        self.index_union(n, &ch, &ctx[n as usize]);
                    }
                }
                &NodeKind::Section(c, _) => todo.push(c),
                NodeKind::Leaf(_) => {}
            }
        }
    }

    /// For each node under `roots`, a box outside which its spans cannot
    /// change its root's, within its own box: its box for a root; for a
    /// child of an operation, the operation's (every operation is
    /// pointwise, and its result lies in its box: a union's the union of
    /// its children's, an intersection's their overlap, a difference's its
    /// first child's), over all its parents, met with the child's box;
    /// a section's child's own box, as it is met along another line (the
    /// ray's foot). Empty for a node the root does not reach. (Children
    /// come before parents, so one pass from the root down has each whole
    /// before its children read it.)
    fn contexts(&self, roots: &[u32]) -> Vec<Aabb> {
        let mut ctx = vec![Aabb::EMPTY; self.nodes.len()];
        for &r in roots {
            ctx[r as usize] = Aabb::EVERYTHING;
        }
        let top = roots.iter().copied().max().unwrap_or(0);
        for i in (0..=top as usize).rev() {
            ctx[i] = ctx[i].intersect(&self.nodes[i].bounds);
            if ctx[i].is_empty() {
                continue;
            }
            match &self.nodes[i].kind {
                NodeKind::Op(_, ch) => {
                    for &c in ch {
                        ctx[c as usize] = ctx[c as usize].union(&ctx[i]);
                    }
                }
                &NodeKind::Section(c, _) => ctx[c as usize] = Aabb::EVERYTHING,
                NodeKind::Leaf(_) => {}
            }
        }
        ctx
    }

    /// Indexes union `n` over `children`, their boxes cut to `within`.
    fn index_union(&mut self, n: u32, children: &[u32], within: &Aabb) {
        let boxes: Vec<Aabb> = children
            .iter()
            .map(|&c| self.nodes[c as usize].bounds.intersect(within))
            .collect();
        // A long primitive lying across the axes (a tilted rod, a beam)
        // fills its box thinly: it is indexed by the boxes of its slices.
        let index = union_index(children, &boxes, |c, b| self.pieces(c, b, 0));
        let sorts = index.as_ref().map_or(true, |ix| !ix.near_first);
        let (mut met, mut lane_ids) = (Vec::new(), Vec::new());
        if sorts && children.len() >= LANES_MIN {
            for (b, &c) in boxes.iter().zip(children) {
                if !b.is_empty() {
                    met.push(*b);
                    lane_ids.push(c);
                }
            }
        }
        let node = &mut self.nodes[n as usize];
        node.index = index;
        node.lanes = met.chunks(4).map(AabbLanes::of).collect();
        node.lane_ids = lane_ids;
        node.pretest = pretest(node);
    }

    /// Boxes that together hold node `n` within its box `whole`, for a
    /// union's hierarchy: a primitive's slices ([`leaf_pieces`]), a
    /// union's children's pieces, a difference's first child's; `whole`
    /// itself where that is all there is, where they would be more than
    /// [`PIECES_CAP`], where they hold more than half its volume, or
    /// below [`PIECES_DEPTH`] levels (`level` is this node's).
    fn pieces(&self, n: u32, whole: &Aabb, level: usize) -> Pieces {
        let alone = smallvec::smallvec![*whole];
        if whole.is_empty() || !whole.is_bounded() || level > PIECES_DEPTH {
            return alone;
        }
        let out: Pieces = match &self.nodes[n as usize].kind {
            NodeKind::Leaf(p) => leaf_pieces(&self.prims[*p as usize], whole),
            NodeKind::Op(Op::Difference, ch) => self.pieces(ch[0], whole, level + 1),
            NodeKind::Op(Op::Union, ch) => {
                let mut all = Pieces::new();
                for &c in ch {
                    let b = self.nodes[c as usize].bounds.intersect(whole);
                    if b.is_empty() {
                        continue;
                    }
                    all.extend(self.pieces(c, &b, level + 1));
                    if all.len() > PIECES_CAP {
                        return alone;
                    }
                }
                all
            }
            _ => return alone,
        };
        if out.len() <= PIECES_CAP
            && out.iter().map(Aabb::volume).sum::<f64>() <= 0.5 * whole.volume()
        {
            out
        } else {
            alone
        }
    }

    fn add_node(&mut self, mut node: Node) -> u32 {
        node.pretest = pretest(&node);
        self.nodes.push(node);
        self.nodes.len() as u32 - 1
    }

    /// The root rays walk: [`Csg::walked`], else the written one.
    fn walked_root(&self) -> Option<u32> {
        self.walked.or(self.root)
    }

    /// The world box of everything (EMPTY for an empty tree).
    pub fn bounds(&self) -> Aabb {
        self.root
            .map_or(Aabb::EMPTY, |r| self.nodes[r as usize].bounds)
    }

    /// The spans of `node` along `ray`. The list agrees with the true solid
    /// on the open range (tmin, tmax); outside it, it may hold anything.
    pub fn spans(&self, node: u32, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> Vec<Span> {
        self.spans_with(node, ray, tmin, tmax, st, <[Span]>::to_vec)
    }

    /// [`Csg::spans`], handed to `f` from the thread's scratch space, so
    /// that no list is allocated.
    pub fn spans_with<R>(
        &self,
        node: u32,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        f: impl FnOnce(&[Span]) -> R,
    ) -> R {
        query(ray, tmin, tmax, st, |q| {
            self.push_spans(node, q);
            f(&q.sc.stack)
        })
    }

    /// Pushes the spans of `node` onto the scratch stack (after what is
    /// there), testing its box first.
    fn push_spans(&self, node: u32, q: &mut Query) {
        // Every box is tested, unbounded ones too: a half-space's box still
        // culls rays that never reach its side, and a box that is empty
        // (a disjoint intersection) at worst lets the spans be computed.
        q.st.bound_tests += 1;
        if !self.nodes[node as usize].bounds.hit(q.ray, q.tmin, q.tmax) {
            q.st.bound_culled += 1;
            return;
        }
        self.push_spans_within(node, q)
    }

    /// [`Csg::push_spans`] for a node whose box the caller has already found
    /// the ray to meet.
    fn push_spans_within(&self, node: u32, q: &mut Query) {
        let n = &self.nodes[node as usize];
        let base = q.sc.stack.len();
        match &n.kind {
            NodeKind::Leaf(p) => self.push_prim_spans(*p, q),
            &NodeKind::Section(c, k) => match self.sections[k as usize].project(q.ray) {
                Some(foot) => self.push_spans(
                    c,
                    &mut Query {
                        ray: &foot,
                        tmin: q.tmin,
                        tmax: q.tmax,
                        st: &mut *q.st,
                        sc: &mut *q.sc,
                    },
                ),
                // Along the frame's z: all of the line or none of it.
                None => {
                    if self.contains(c, self.sections[k as usize].foot(q.ray.origin)) {
                        q.sc.stack.push(Span {
                            enter: Boundary::open(f64::NEG_INFINITY),
                            exit: Boundary::open(f64::INFINITY),
                        });
                    }
                }
            },
            NodeKind::Op(Op::Union, ch) => {
                let mut hit: SmallVec<[u32; 32]> = SmallVec::new();
                // The children the ray may meet, and how many of them, at
                // the front, still have their boxes to be tested.
                let (ch, untested): (&[u32], usize) = match &n.index {
                    Some(ix) => {
                        // The unbounded children, their boxes tested; then
                        // those the hierarchy finds, each by a box of its
                        // own within its node's box (cut to where the union
                        // matters, or a piece of that), so that the node's
                        // box, the same slab test on wider sides, passes
                        // too and is not tested again.
                        hit.extend_from_slice(&ix.unbounded);
                        ix.bvh.visit(q.ray, q.tmin, q.tmax, q.st, |c| {
                            if !ix.split || !hit.contains(&c) {
                                hit.push(c)
                            }
                        });
                        (&hit, ix.unbounded.len())
                    }
                    None if !n.lanes.is_empty() => {
                        // The children's boxes four at once (cut to where
                        // the union matters, as the lanes are: a child met
                        // there meets its own box).
                        AabbLanes::gather(&n.lanes, &n.lane_ids, q.ray, q.tmin, q.tmax, |_, c| {
                            hit.push(c)
                        });
                        q.st.bound_tests += n.lane_ids.len() as u64;
                        q.st.bound_culled += (n.lane_ids.len() - hit.len()) as u64;
                        (&hit, 0)
                    }
                    None => (ch, ch.len()),
                };
                for (k, &c) in ch.iter().enumerate() {
                    let top = q.sc.stack.len();
                    if k < untested {
                        self.push_spans(c, q);
                    } else {
                        self.push_spans_within(c, q);
                    }
                    q.sc.merge(Op::Union, base, top, q.ray);
                }
            }
            &NodeKind::Op(Op::Xor, ref ch) => {
                // Every child matters over the whole ray.
                self.push_spans(ch[0], q);
                for &c in &ch[1..] {
                    let top = q.sc.stack.len();
                    self.push_spans(c, q);
                    q.sc.merge(Op::Xor, base, top, q.ray);
                }
            }
            &NodeKind::Op(op, ref ch) => {
                self.push_spans(ch[0], q);
                for &c in &ch[1..] {
                    let acc = &q.sc.stack[base..];
                    let (Some(first), Some(last)) = (acc.first(), acc.last()) else {
                        break;
                    };
                    // Later children matter only where the result may be.
                    let lo = q.tmin.max(first.enter.t);
                    let hi = q.tmax.min(last.exit.t);
                    let top = q.sc.stack.len();
                    self.push_spans(c, &mut q.within(lo, hi));
                    q.sc.merge(op, base, top, q.ray);
                }
            }
        }
        q.st.max_spans = q.st.max_spans.max((q.sc.stack.len() - base) as u64);
    }

    fn push_prim_spans(&self, id: u32, q: &mut Query) {
        let stack = &mut q.sc.stack;
        self.prim_spans(id, q.ray, q.tmin, q.tmax, Need::Spans, q.st, |s| {
            stack.push(s)
        });
    }

    /// Calls `emit` with the spans of primitive `id` along `ray` (see
    /// [`Solid::spans`](crate::geometry::solid::Solid::spans)), asked for
    /// `need`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn prim_spans(
        &self,
        id: u32,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        need: Need,
        st: &mut Stats,
        mut emit: impl FnMut(Span),
    ) {
        st.primitive_tests += 1;
        let p = &self.prims[id as usize];
        let (o, d) = p.xf.ray_to_object(ray);
        let mut probe = Probe {
            o,
            d,
            tmin,
            tmax,
            st,
            need,
        };
        p.shape.spans(&mut probe, &mut |(t0, p0, t1, p1)| {
            let b = |t, part| Boundary::new(t, id, part);
            emit(Span {
                enter: b(t0, p0),
                exit: b(t1, p1),
            })
        });
    }

    /// [`Csg::first_boundary_for`] of a tree that is one leaf, primitive
    /// `id`: its first surface boundary read off its spans as they come,
    /// with no scratch list (its box tested first, as any node's).
    #[allow(clippy::too_many_arguments)]
    fn leaf_first(
        &self,
        node: u32,
        id: u32,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        need: Need,
    ) -> Option<Boundary> {
        st.bound_tests += 1;
        if !self.nodes[node as usize].bounds.hit(ray, tmin, tmax) {
            st.bound_culled += 1;
            return None;
        }
        let (mut first, mut count) = (None, 0u64);
        self.prim_spans(id, ray, tmin, tmax, need, st, |s| {
            count += 1;
            if first.is_none() {
                // The rule of first_surface on the span's two boundaries, taken
                // by value (by reference, the chosen one was read back
                // from memory as one 16-byte load of two 8-byte stores).
                first = [s.enter, s.exit]
                    .into_iter()
                    .find(|b| surface_after(b, tmin));
            }
        });
        // The leaf's list, counted as if held.
        st.max_spans = st.max_spans.max(count);
        first.filter(|b| b.t < tmax)
    }

    /// The first surface boundary with `tmin < t < tmax`, if any.
    pub fn first_boundary(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
    ) -> Option<Boundary> {
        self.first_boundary_for(ray, tmin, tmax, st, Need::FirstBoundary)
    }

    /// [`Csg::first_boundary`], where a leaf that is the whole tree is
    /// asked only for `need`: its first boundary is the tree's.
    fn first_boundary_for(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        need: Need,
    ) -> Option<Boundary> {
        let root = self.walked_root()?;
        if let NodeKind::Leaf(id) = self.nodes[root as usize].kind {
            return self.leaf_first(root, id, ray, tmin, tmax, st, need);
        }
        if !self.root_box(root, ray, tmin, tmax, st) {
            return None;
        }
        query(ray, tmin, tmax, st, |q| {
            self.push_root(root, q, |acc| first_surface(acc, tmin));
            first_surface(&q.sc.stack, tmin).filter(|b| b.t < tmax)
        })
    }

    /// Whether the ray may meet the root's own box: tested before a query
    /// is set up (the thread's scratch, the query's frame: some 100
    /// instructions, which a ray that misses the whole scene — most of a
    /// background — need not pay) where [`Node::pretest`] says so, else
    /// left to the root's walk (true here).
    ///
    /// A ray that misses a union's box misses every child's box within it
    /// (each of the box test's slab ranges holds a child's), so nothing
    /// changes but the boxes not tested one by one; any other node's walk
    /// would test its box first ([`Csg::push_spans`]), counted the same.
    /// Not an unbounded box, such as a floor's, which every ray meets; an
    /// empty box is tested, and culls, as it should. Not a union that
    /// walks its hierarchy, whose walk begins with the hierarchy's own box.
    #[inline(always)]
    fn root_box(&self, root: u32, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> bool {
        let n = &self.nodes[root as usize];
        if n.pretest {
            st.bound_tests += 1;
            if !n.bounds.hit(ray, tmin, tmax) {
                st.bound_culled += 1;
                return false;
            }
        }
        true
    }

    /// Pushes the spans of `root`, the whole tree, whose box the ray meets
    /// if [`Csg::root_box`] has tested it: a union's good up to the
    /// boundary `first` finds in them ([`Csg::union_first`]), any other
    /// node's whole.
    fn push_root(&self, root: u32, q: &mut Query, first: impl Fn(&[Span]) -> Option<Boundary>) {
        let n = &self.nodes[root as usize];
        match &n.kind {
            NodeKind::Op(Op::Union, ch) => self.union_first(root, ch, q, first),
            _ if n.pretest => self.push_spans_within(root, q),
            _ => self.push_spans(root, q),
        }
    }

    /// The whole tree's spans along `ray` handed to `f`, good up to the
    /// entry of the first span after `tmin` that `stops` (a surface
    /// entered: what lies beyond it is not needed), and over all of (tmin,
    /// tmax) when none does.
    pub fn spans_until<R>(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        stops: impl Fn(&Boundary) -> bool,
        f: impl FnOnce(&[Span]) -> R,
    ) -> R {
        let Some(root) = self.walked_root() else {
            return f(&[]);
        };
        let first = |acc: &[Span]| {
            acc.iter()
                .map(|s| s.enter)
                .find(|b| surface_after(b, tmin) && stops(b))
        };
        if !self.root_box(root, ray, tmin, tmax, st) {
            return f(&[]);
        }
        query(ray, tmin, tmax, st, |q| {
            self.push_root(root, q, first);
            f(&q.sc.stack)
        })
    }

    /// Pushes the root union's spans, good up to the boundary `first`
    /// finds in them (its first boundary after `tmin`, say), or whole if
    /// it finds none.
    ///
    /// Children are taken in the order the ray enters their boxes; once the
    /// next box begins beyond the boundary found, no child left can
    /// change the result before that boundary, and the walk stops.
    fn union_first(
        &self,
        node: u32,
        ch: &[u32],
        q: &mut Query,
        first: impl Fn(&[Span]) -> Option<Boundary>,
    ) {
        let n = &self.nodes[node as usize];
        let (ray, tmin, tmax) = (q.ray, q.tmin, q.tmax);
        let scale = ray.origin.abs().max_element();
        let base = q.sc.stack.len();
        // Every child reaching `add` has had its box tested already.
        let add = |c, q: &mut Query| {
            let top = q.sc.stack.len();
            self.push_spans_within(c, q);
            q.sc.merge(Op::Union, base, top, ray);
        };
        // A child whose box begins at the first boundary may touch it and
        // merge it away (a part standing on a floor), and boundaries within
        // the coincidence bound are one: only boxes beyond that are cut.
        let cut = |acc: &[Span]| {
            first(acc).map_or(f64::INFINITY, |b| b.t + 2.0 * coincidence(b.t, scale))
        };
        // The hierarchy pays for wide unions and for those whose children
        // lie apart (see [`FILL_MAX`]); measured at 640×480 with one
        // thread, 12 nested tori render in 0.50 s by sorting and 0.63 s
        // through it, the lecture's seed scene in 0.13 s and 0.19 s.
        if let Some(ix) = n.index.as_ref().filter(|ix| ix.near_first) {
            for &c in &ix.unbounded {
                add(c, q);
            }
            // The walk keeps the counters; each visit gets them back for
            // the child's own query.
            let sc = &mut *q.sc;
            // The children held by several boxes already asked.
            let mut asked: SmallVec<[u32; 16]> = SmallVec::new();
            ix.bvh.visit_near_first(ray, tmin, tmax, q.st, |c, st| {
                if ix.split {
                    if asked.contains(&c) {
                        return cut(&sc.stack[base..]);
                    }
                    asked.push(c);
                }
                let mut child = Query {
                    ray,
                    tmin,
                    tmax,
                    st,
                    sc: &mut *sc,
                };
                add(c, &mut child);
                cut(&child.sc.stack[base..])
            });
            return;
        }
        // The union's own box has been tested by [`Csg::root_box`] (the
        // root is the only union walked here) if it is bounded.
        let mut order: SmallVec<[(f64, u32); 32]> = SmallVec::new();
        if n.lanes.is_empty() {
            for &c in ch {
                q.st.bound_tests += 1;
                match self.nodes[c as usize].bounds.entry(ray, tmin, tmax) {
                    Some(t) => order.push((t, c)),
                    None => q.st.bound_culled += 1,
                }
            }
        } else {
            // The same entries, four boxes at once.
            AabbLanes::gather(&n.lanes, &n.lane_ids, ray, tmin, tmax, |t, c| {
                order.push((t, c))
            });
            q.st.bound_tests += n.lane_ids.len() as u64;
            q.st.bound_culled += (n.lane_ids.len() - order.len()) as u64;
        }
        // Entries are never NaN (the box test keeps `tmin` over NaN). (The
        // closure, not the function itself: the sort compiled from the
        // function took 0.7 % more of nested_tori's instructions and 1.3 %
        // more of seed's.)
        #[allow(clippy::redundant_closure)]
        order.sort_unstable_by(|a, b| by_entry(a, b));
        // The cut of what has been added so far (nothing yet: none).
        let mut now = f64::INFINITY;
        for &(entry, c) in &order {
            if entry > now {
                break;
            }
            add(c, q);
            now = cut(&q.sc.stack[base..]);
        }
    }

    /// The first surface the ray hits in (tmin, tmax), with its normal.
    pub fn first_hit(&self, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> Option<SurfaceHit> {
        let b = self.first_boundary(ray, tmin, tmax, st)?;
        Some(self.surface(ray, &b, st))
    }

    /// Whether anything lies on the ray in (tmin, tmax).
    pub fn occluded(&self, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> bool {
        self.first_boundary_for(ray, tmin, tmax, st, Need::AnyBoundary)
            .is_some()
    }

    /// Point and unit outward normal of a boundary found along `ray`.
    pub fn surface(&self, ray: &Ray, b: &Boundary, st: &mut Stats) -> SurfaceHit {
        st.normals_computed += 1;
        let p = &self.prims[b.prim as usize];
        let n = match (p.section, &p.faces) {
            (None, Some(faces)) => faces[b.part() as usize],
            _ => self.normal_along(p, ray, b),
        };
        SurfaceHit {
            t: b.t,
            point: ray.at(b.t),
            normal: if b.flip() && !crate::mutant::active("difference_unflipped") {
                -n
            } else {
                n
            },
            prim: b.prim,
        }
    }

    /// The unit world normal of primitive `p` where `ray` meets it at
    /// boundary `b`, found along the ray in object space.
    fn normal_along(&self, p: &Primitive, ray: &Ray, b: &Boundary) -> DVec3 {
        // A primitive in sections is met along the ray's foot in each,
        // the outermost first; its normal flattened from the innermost out.
        let mut chain: SmallVec<[u32; 4]> = SmallVec::new();
        let mut at = p.section;
        while let Some(k) = at {
            chain.push(k);
            at = self.sections[k as usize].outer;
        }
        let mut foot = *ray;
        for &k in chain.iter().rev() {
            if let Some(r) = self.sections[k as usize].project(&foot) {
                foot = r;
            }
        }
        let (o, d) = p.xf.ray_to_object(&foot);
        let n_obj = p.shape.normal_on(o, d, b.t, b.part());
        let mut n = p.xf.normal_to_world(n_obj);
        for &k in &chain {
            n = self.sections[k as usize].normal(n);
        }
        n
    }

    /// Whether a world point is inside the solid (boundaries count as in).
    pub fn contains(&self, node: u32, p: DVec3) -> bool {
        match &self.nodes[node as usize].kind {
            NodeKind::Leaf(i) => {
                let prim = &self.prims[*i as usize];
                prim.shape.contains(prim.xf.point_to_object(p))
            }
            &NodeKind::Section(c, k) => self.contains(c, self.sections[k as usize].foot(p)),
            NodeKind::Op(Op::Union, ch) => ch.iter().any(|&c| self.contains(c, p)),
            NodeKind::Op(Op::Intersection, ch) => ch.iter().all(|&c| self.contains(c, p)),
            NodeKind::Op(Op::Difference, ch) => {
                self.contains(ch[0], p) && !ch[1..].iter().any(|&c| self.contains(c, p))
            }
            NodeKind::Op(Op::Xor, ch) => {
                ch.iter().filter(|&&c| self.contains(c, p)).count() % 2 == 1
            }
        }
    }
}

/// The hierarchy of a union over `children`, whose boxes (cut to where
/// the union matters) are `boxes`: none for fewer than
/// [`UNION_INDEX_MIN`] bounded ones. A child whose box is empty there is
/// left out; one whose box is unbounded is always looked at. The
/// hierarchy holds each bounded child by the boxes `pieces` gives it.
fn union_index(
    children: &[u32],
    boxes: &[Aabb],
    pieces: impl Fn(u32, &Aabb) -> Pieces,
) -> Option<Box<UnionIndex>> {
    let met = children.iter().zip(boxes).filter(|(_, b)| !b.is_empty());
    let items: Vec<(u32, Aabb)> = met
        .clone()
        .filter(|(_, b)| b.is_bounded())
        .map(|(&c, &b)| (c, b))
        .collect();
    let unbounded: Vec<u32> = met
        .filter(|(_, b)| !b.is_bounded())
        .map(|(&c, _)| c)
        .collect();
    if items.len() < UNION_INDEX_MIN {
        return None;
    }
    // The hierarchy's items: each bounded child by its pieces.
    let (mut refs, mut split) = (Vec::with_capacity(items.len()), false);
    for &(c, b) in &items {
        let ps = pieces(c, &b);
        split |= ps.len() > 1;
        refs.extend(ps.into_iter().map(|p| (c, p)));
    }
    let bvh = Bvh::build(&refs, UNION_LEAF);
    let root = items.iter().fold(Aabb::EMPTY, |a, x| a.union(&x.1));
    // (A flat union's box has no volume: ∞ or NaN, never below.)
    let fill: f64 = items.iter().map(|x| x.1.volume()).sum::<f64>() / root.volume();
    // A child held by pieces (at most half its box) is found by them only
    // through the hierarchy: sorting takes its whole box.
    let near_first = items.len() > BEST_FIRST_MIN || fill < FILL_MAX || split;
    Some(Box::new(UnionIndex {
        near_first,
        bvh,
        unbounded,
        split,
    }))
}

/// The most slices [`leaf_pieces`] cuts a primitive into.
pub const PIECES_MAX: usize = 8;

/// The most boxes [`Csg::pieces`] holds a union's child by.
pub const PIECES_CAP: usize = 32;

/// How deep below a union's child [`Csg::pieces`] looks (a tree may nest
/// 4,096 levels: the walk stays well within a thread's stack).
pub const PIECES_DEPTH: usize = 32;

/// A node's boxes for a union's hierarchy.
type Pieces = SmallVec<[Aabb; PIECES_MAX]>;

/// The boxes a union's hierarchy may hold primitive `p` by, within its
/// box `whole` (bounded, not empty): the world boxes of its slices across
/// one object axis ([`Solid::slab_bounds`](crate::geometry::solid::Solid::slab_bounds)),
/// each met with `whole` — for a primitive whose object box is long in
/// the world (its longest side at least twice its others), across that
/// side, as many slices as it is times longer; for one whose slabs narrow
/// or turn (a twisted or tapered prism), across that axis; at most
/// [`PIECES_MAX`] — else `whole` itself. Every point of the primitive
/// lies in one of them; [`Csg::pieces`] keeps them where they pay.
fn leaf_pieces(p: &Primitive, whole: &Aabb) -> Pieces {
    let alone = smallvec::smallvec![*whole];
    let ob = p.shape.object_bounds();
    if p.section.is_some() || !ob.is_bounded() {
        return alone;
    }
    let m = &p.xf.to_world;
    let ext = ob.max - ob.min;
    let len = DVec3::new(
        (m.matrix3.x_axis * ext.x).length(),
        (m.matrix3.y_axis * ext.y).length(),
        (m.matrix3.z_axis * ext.z).length(),
    );
    let long = (0..3).fold(0, |a, i| if len[i] > len[a] { i } else { a });
    let rest = (0..3)
        .filter(|&i| i != long)
        .map(|i| len[i])
        .fold(0.0, f64::max);
    let k = (len[long] / rest).floor().min(PIECES_MAX as f64);
    let (axis, k) = if k >= 2.0 {
        (long, k as usize)
    } else if let Some(axis) = p.shape.narrowing_axis() {
        (axis, PIECES_MAX)
    } else {
        return alone;
    };
    let at = |i: usize| ob.min[axis] + ext[axis] * (i as f64 / k as f64);
    let mut out = SmallVec::new();
    // (The mutant forgets the last slice.)
    let slices = if crate::mutant::active("pieces_last_dropped") {
        k - 1
    } else {
        k
    };
    for i in 0..slices {
        let hi = if i + 1 == k { ob.max[axis] } else { at(i + 1) };
        let b = p.shape.slab_bounds(axis, at(i), hi);
        let w = crate::geometry::solid::corner_box(&b, m).intersect(whole);
        if !w.is_empty() {
            out.push(w);
        }
    }
    out
}

/// Whether a node's box is tested before its spans (a bounded one whose
/// union does not walk its own hierarchy nearest first).
fn pretest(node: &Node) -> bool {
    let e = node.bounds.max - node.bounds.min;
    e.x + e.y + e.z < f64::INFINITY && !node.index.as_ref().is_some_and(|ix| ix.near_first)
}

/// The box of an operation from its children's (in order): a union's or
/// symmetric difference's join, an intersection's overlap, a difference's
/// first child's.
fn op_bounds(op: Op, mut boxes: impl Iterator<Item = Aabb>) -> Aabb {
    match op {
        Op::Union | Op::Xor => boxes.fold(Aabb::EMPTY, |a, x| a.union(&x)),
        Op::Intersection => {
            let b = boxes.fold(Aabb::EVERYTHING, |a, x| a.intersect(&x));
            // Boxes apart meet in nothing: not in a box whose sides
            // cross, which a union would then take sides from.
            if b.is_empty() {
                Aabb::EMPTY
            } else {
                b
            }
        }
        Op::Difference => boxes.next().unwrap_or(Aabb::EMPTY),
    }
}

/// How far [`Csg::add_op`] counts an intersection's children's leaves
/// to order them: a bound on the work of one node's count.
const LEAF_COUNT_CAP: usize = 256;

/// From how many children a union's first-hit query walks its hierarchy,
/// nearer subtrees first, instead of sorting every child the ray meets.
pub const BEST_FIRST_MIN: usize = 64;

/// Below this many children, a union's first-hit query walks its hierarchy
/// only if the children's boxes fill less than this share of the union's
/// box (their volumes summed), or a child is held by pieces
/// ([`Csg::pieces`]), which only the hierarchy holds it by: boxes apart
/// (a row of turned parts, the glyphs of a text) leave most subtrees unopened, boxes nested about one
/// another (interlocked tori) make the walk open nearly every box and pay
/// its own bookkeeping besides. Measured by instructions at 640×480 on one
/// thread (callgrind): twelve lathes (fill 0.26) 1.53 → 1.38 G, the glass
/// model (its unions 0.16–1.0) 4.87 → 4.47 G through the hierarchy; the
/// lecture's seed scene (1.13, 2.02) and twelve interlocked tori (2.24)
/// 17 % and 14 % more that way, so they sort.
pub const FILL_MAX: f64 = 1.0;

/// Children met by a ray, by box entry, then child: for entries that are
/// not NaN and distinct children a total order, so a sort gives the one
/// order whatever its algorithm — the order of the tuples' `partial_cmp`,
/// which took half as many instructions again in the sort (nested_tori:
/// 44 against 29 M of 830 M).
#[inline(always)]
fn by_entry(a: &(f64, u32), b: &(f64, u32)) -> std::cmp::Ordering {
    if a.0 < b.0 {
        std::cmp::Ordering::Less
    } else if a.0 > b.0 {
        std::cmp::Ordering::Greater
    } else {
        a.1.cmp(&b.1)
    }
}

/// Whether `b` is a real surface crossing after `tmin`: what a first hit
/// looks for.
#[inline(always)]
fn surface_after(b: &Boundary, tmin: f64) -> bool {
    b.t > tmin && b.is_surface()
}

/// The first real surface crossing after `tmin` in a list.
fn first_surface(list: &[Span], tmin: f64) -> Option<Boundary> {
    // A plain loop, not a flat_map over each span's two boundaries (with
    // the cut taken once a child is added: 2 % fewer instructions on the
    // primitives model).
    for s in list {
        for b in [&s.enter, &s.exit] {
            if surface_after(b, tmin) {
                return Some(*b);
            }
        }
    }
    None
}

/// Spans a thread reserves for its queries before any query runs; a query
/// that needs more grows the buffer once (counted in `span_allocations`).
pub const SCRATCH_SPANS: usize = 256;

/// One span query in flight: the ray, the range of t it asks about, the
/// counters and the scratch stack its lists are built on.
struct Query<'a> {
    ray: &'a Ray,
    tmin: f64,
    tmax: f64,
    st: &'a mut Stats,
    sc: &'a mut Scratch,
}

/// Runs `f` on a query over (tmin, tmax) built on this thread's scratch.
fn query<R>(ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats, f: impl FnOnce(&mut Query) -> R) -> R {
    with_scratch(st, |sc, st| {
        f(&mut Query {
            ray,
            tmin,
            tmax,
            st,
            sc,
        })
    })
}

impl Query<'_> {
    /// The same query over [lo, hi] only (the later children of an
    /// intersection or a difference).
    fn within(&mut self, lo: f64, hi: f64) -> Query<'_> {
        Query {
            ray: self.ray,
            tmin: lo,
            tmax: hi,
            st: &mut *self.st,
            sc: &mut *self.sc,
        }
    }
}

/// A thread's working space for span queries. Nodes push their results on
/// `stack`, each above its parent's; a combination is written to `out` and
/// copied back down, so no list is ever allocated or moved whole.
struct Scratch {
    stack: Vec<Span>,
    out: Vec<Span>,
}

impl Scratch {
    fn new() -> Scratch {
        Scratch {
            stack: Vec::with_capacity(SCRATCH_SPANS),
            out: Vec::with_capacity(SCRATCH_SPANS),
        }
    }

    /// Replaces `stack[base..top]` (A) and `stack[top..]` (B) by `A op B`,
    /// in place where [`spans::quick`] allows. A side that is empty (a
    /// child the ray missed: most merges) is answered here, inline, by
    /// [`spans::quick_empty`].
    #[inline]
    fn merge(&mut self, op: Op, base: usize, top: usize, ray: &Ray) {
        if top == base || self.stack.len() == top {
            // A and B as they stand, or nothing.
            let (a, b) = self.stack[base..].split_at(top - base);
            let empty = spans::quick_empty(op, a, b) == Some(Quick::Empty);
            if empty && !crate::mutant::active("merge_empty_kept") {
                self.stack.truncate(base);
            }
            return;
        }
        self.merge_both(op, base, top, ray);
    }

    /// [`Scratch::merge`] of two sides that both hold spans.
    fn merge_both(&mut self, op: Op, base: usize, top: usize, ray: &Ray) {
        let (a, b) = self.stack[base..].split_at(top - base);
        let scale = ray.origin.abs().max_element();
        let quick = (op == Op::Union)
            .then(|| spans::apart(a, b, scale))
            .flatten();
        match quick {
            // Nothing to do: A stays, B is the whole result and, A being
            // empty, already sits where A would be, or B follows A.
            Some(Quick::A | Quick::B | Quick::AThenB) => return,
            Some(Quick::Empty) => {
                self.stack.truncate(base);
                return;
            }
            Some(Quick::BThenA) => {
                let nb = b.len();
                self.stack[base..].rotate_right(nb);
                return;
            }
            None => {}
        }
        // Two single spans: written out, not swept (the same answer).
        if let Some((r, n)) = spans::single(op, a, b, scale) {
            self.stack[base..base + n].copy_from_slice(&r[..n]);
            self.stack.truncate(base + n);
            return;
        }
        self.out.clear();
        // Only A's spans that B's ends come near take part: those wholly
        // before B's first span, or wholly after its last one, the sweep
        // meets one end at a time with B nowhere near, outside B — it keeps
        // them as they are (an intersection drops them). A is sorted, so
        // they are a prefix and a suffix, found by bisection: a union of
        // many children merged one at a time sweeps what each one touches,
        // not everything merged so far.
        let (first, last) = (&b[0], &b[b.len() - 1]);
        let p = a.partition_point(|s| spans::ends_before(s, first, scale));
        let q = p + a[p..].partition_point(|s| !spans::ends_before(last, s, scale));
        if p > 0 || q < a.len() {
            let keep = op.apply(true, false);
            spans::combine_into(op, &a[p..q], b, scale, &mut self.out);
            if keep {
                self.out.extend_from_slice(&a[q..]);
            }
            self.stack.truncate(base + if keep { p } else { 0 });
            self.stack.extend_from_slice(&self.out);
            return;
        }
        spans::sweep_into(op, a, b, scale, &mut self.out);
        self.stack.truncate(base);
        self.stack.extend_from_slice(&self.out);
    }
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::new());
}

/// Runs a query on this thread's scratch space, emptied first (or on a
/// fresh one if a query is already running on this thread).
fn with_scratch<R>(st: &mut Stats, f: impl FnOnce(&mut Scratch, &mut Stats) -> R) -> R {
    SCRATCH.with(|cell| {
        let Ok(mut sc) = cell.try_borrow_mut() else {
            st.span_allocations += 1;
            return f(&mut Scratch::new(), st);
        };
        sc.stack.clear();
        let cap = (sc.stack.capacity(), sc.out.capacity());
        let r = f(&mut sc, st);
        if (sc.stack.capacity(), sc.out.capacity()) != cap {
            st.span_allocations += 1;
        }
        r
    })
}

#[cfg(test)]
mod tests {
    use super::{by_entry, Op};
    use proptest::prelude::*;

    /// Every point of a node lies in one of the boxes [`super::Csg::pieces`]
    /// holds it by, and long tilted rods are held by slices: checked at
    /// 40,000 points of unions and differences of rods, boxes and balls
    /// in random places.
    #[test]
    fn a_node_lies_within_its_pieces() {
        use super::{Csg, NodeKind, Op, Primitive};
        use crate::geometry::{Cone, Cuboid, Shape, Sphere, Transform};
        use glam::{DAffine3, DQuat, DVec3};
        let mut rnd = crate::plane::tests::uniform(3);
        let mut split = 0;
        for round in 0..40 {
            let mut csg = Csg::default();
            let leaf = |csg: &mut Csg, rnd: &mut dyn FnMut() -> f64| {
                let shape = match (rnd() * 3.0) as u32 {
                    0 => Shape::Cone(Cone {
                        r0: 1.0,
                        r1: 0.3 + 0.7 * rnd(),
                        centered: rnd() < 0.5,
                    }),
                    1 => Shape::Cuboid(Cuboid { centered: false }),
                    _ => Shape::Sphere(Sphere),
                };
                let axis = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
                let m = DAffine3::from_scale_rotation_translation(
                    DVec3::new(0.2 + rnd(), 0.2 + rnd(), 1.0 + 30.0 * rnd()),
                    DQuat::from_axis_angle(axis, 3.0 * rnd()),
                    DVec3::new(20.0 * rnd(), 20.0 * rnd(), 20.0 * rnd()),
                );
                csg.add_prim(Primitive::new(shape, Transform::new(m).unwrap(), 0))
            };
            let mut parts = Vec::new();
            for _ in 0..3 {
                let a: Vec<u32> = (0..3).map(|_| leaf(&mut csg, &mut rnd)).collect();
                let u = csg.add_op(Op::Union, a);
                let b = leaf(&mut csg, &mut rnd);
                parts.push(csg.add_op(Op::Difference, vec![u, b]));
            }
            let root = csg.add_op(Op::Union, parts);
            csg.root = Some(root);
            for n in 0..csg.nodes.len() as u32 {
                let whole = csg.nodes[n as usize].bounds;
                let pieces = csg.pieces(n, &whole, 0);
                if pieces.len() > 1 {
                    split += 1;
                }
                let (lo, hi) = (whole.min, whole.max);
                for _ in 0..1000 {
                    let p = lo + (hi - lo) * DVec3::new(rnd(), rnd(), rnd());
                    if !csg.contains(n, p) {
                        continue;
                    }
                    assert!(
                        pieces
                            .iter()
                            .any(|b| (b.min.cmple(p) & p.cmple(b.max)).all()),
                        "round {round}, node {n} ({:?}): {p} in no piece of {pieces:?}",
                        matches!(csg.nodes[n as usize].kind, NodeKind::Leaf(_))
                    );
                }
            }
        }
        assert!(split > 50, "{split} nodes split");
    }

    proptest! {
        /// The written-out order is the tuples' own, ties in the entry
        /// (zeros of both signs among them) broken by the child.
        #[test]
        fn children_sort_as_their_tuples_do(
            entries in proptest::collection::vec(
                prop_oneof![Just(0.0), Just(-0.0), Just(1.0), Just(f64::INFINITY), -5.0..5.0f64],
                0..40,
            ),
        ) {
            // Distinct children, in an order unrelated to the entries'.
            let v: Vec<(f64, u32)> = entries
                .iter()
                .enumerate()
                .map(|(k, &t)| (t, (k as u32 * 7919) % 1009))
                .collect();
            let mut want = v.clone();
            want.sort_by(|a, b| a.partial_cmp(b).unwrap());
            let mut got = v;
            got.sort_unstable_by(by_entry);
            let bits = |l: &[(f64, u32)]| l.iter().map(|x| (x.0.to_bits(), x.1)).collect::<Vec<_>>();
            prop_assert_eq!(bits(&got), bits(&want));
        }

        /// Lists merged on the scratch stack, where only the spans of A
        /// that B comes near are swept, are the one sweep over both lists,
        /// boundary for boundary: on sorted lists whose ends sit on a
        /// coarse grid moved by a few units of the coincidence bound, so
        /// that ends coincide, nearly touch and lie apart.
        #[test]
        fn a_merge_spliced_is_the_whole_sweep(
            a in proptest::collection::vec((0u32..3, 0u32..3, -2i32..3), 0..12),
            b in proptest::collection::vec((0u32..3, 0u32..3, -2i32..3), 1..4),
            start in 0u32..6,
        ) {
            use super::{Scratch, Span};
            use crate::csg::spans::{combine, Boundary};
            use crate::geometry::Ray;
            use glam::DVec3;
            let scale = 10.0;
            let bound = crate::math::robust::coincidence(50.0, scale);
            // Each list sorted: gaps and lengths in grid steps, each end
            // moved by a multiple of half the coincidence bound.
            let list = |v: &[(u32, u32, i32)], from: u32, prim: u32| {
                let mut t = from as f64;
                v.iter()
                    .map(|&(gap, len, wiggle)| {
                        let enter = (t + gap as f64 + wiggle as f64 * 0.5 * bound).max(t);
                        let exit = enter.max(t + (gap + len) as f64);
                        t = exit;
                        Span { enter: Boundary::new(enter, prim, 0), exit: Boundary::new(exit, prim, 1) }
                    })
                    .collect::<Vec<_>>()
            };
            let (a, b) = (list(&a, 0, 0), list(&b, start, 1));
            let ray = Ray::new(DVec3::new(scale, 0.0, 0.0), DVec3::X);
            let key = |l: &[Span]| {
                l.iter()
                    .map(|s| {
                        let end = |x: &Boundary| (x.t.to_bits(), x.prim, x.part(), x.flip());
                        (end(&s.enter), end(&s.exit))
                    })
                    .collect::<Vec<_>>()
            };
            for op in [Op::Union, Op::Intersection, Op::Difference, Op::Xor] {
                let want = combine(op, &a, &b, scale);
                let mut sc = Scratch::new();
                sc.stack.extend_from_slice(&a);
                sc.stack.extend_from_slice(&b);
                sc.merge(op, 0, a.len(), &ray);
                prop_assert_eq!(key(&sc.stack), key(&want), "{:?}", op);
            }
        }
    }
}
