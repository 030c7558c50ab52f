//! The CSG tree and the queries every node answers: its bounds, its spans
//! along a ray, the first surface a ray hits, and point membership.
//!
//! As slides 38–40 of the seed lecture: leaves return their entry/exit
//! lists, each node combines its children's lists from the leaves to the
//! root, and a difference flips the normals of the surfaces it takes from
//! its subtracted children. The normal and material are looked up only for
//! the boundary that wins ([`Csg::surface`]).

pub mod bvh;
pub mod spans;

use crate::geometry::robust::coincidence;
use crate::geometry::{Aabb, Ray, Shape, Transform};
use crate::stats::Stats;
use bvh::Bvh;
use glam::DVec3;
use smallvec::SmallVec;
use spans::{combine, Boundary, Op, Span, SpanList};

/// A primitive placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    pub shape: Shape,
    pub xf: Transform,
    /// Index into the scene's materials.
    pub material: u32,
    /// World bounding box ([`Aabb::EVERYTHING`] if unbounded).
    pub bounds: Aabb,
}

impl Primitive {
    pub fn new(shape: Shape, xf: Transform, material: u32) -> Primitive {
        let bounds = shape.world_bounds(&xf.to_world);
        Primitive {
            shape,
            xf,
            material,
            bounds,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    Leaf(u32),
    Union(Vec<u32>),
    Intersection(Vec<u32>),
    /// The first child minus the rest.
    Difference(Vec<u32>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub kind: NodeKind,
    /// World box: the union of a union's children, the overlap of an
    /// intersection's, a difference's first child's.
    pub bounds: Aabb,
    /// For a union of many children: a hierarchy over the bounded ones.
    pub index: Option<Box<UnionIndex>>,
}

/// How a wide union finds the children a ray may meet.
#[derive(Clone, Debug, PartialEq)]
pub struct UnionIndex {
    pub bvh: Bvh,
    /// Children without a finite box (halfspaces), always looked at.
    pub unbounded: Vec<u32>,
}

/// A CSG tree over its primitives. Node ids index `nodes`; children come
/// before their parents.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Csg {
    pub prims: Vec<Primitive>,
    pub nodes: Vec<Node>,
    pub root: Option<u32>,
}

/// A surface point found by a query, with its unit outward normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    pub t: f64,
    pub point: DVec3,
    pub normal: DVec3,
    pub prim: u32,
}

impl Csg {
    pub fn add_prim(&mut self, prim: Primitive) -> u32 {
        let bounds = prim.bounds;
        self.prims.push(prim);
        let id = self.prims.len() as u32 - 1;
        self.add_node(Node {
            kind: NodeKind::Leaf(id),
            bounds,
            index: None,
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
                    NodeKind::Union(ch) => ch.clone(),
                    _ => vec![c],
                })
                .collect();
        }
        if op == Op::Difference && children.len() > 2 {
            let rest = children.split_off(1);
            let u = self.add_op(Op::Union, rest);
            children.push(u);
        }
        let b = |i: &u32| self.nodes[*i as usize].bounds;
        let bounds = match op {
            Op::Union => children.iter().map(b).fold(Aabb::EMPTY, |a, x| a.union(&x)),
            Op::Intersection => children
                .iter()
                .map(b)
                .fold(Aabb::EVERYTHING, |a, x| a.intersect(&x)),
            Op::Difference => b(&children[0]),
        };
        let index = if op == Op::Union {
            self.union_index(&children)
        } else {
            None
        };
        let kind = match op {
            Op::Union => NodeKind::Union(children),
            Op::Intersection => NodeKind::Intersection(children),
            Op::Difference => NodeKind::Difference(children),
        };
        let mut node = Node {
            kind,
            bounds,
            index: None,
        };
        node.index = index;
        self.add_node(node)
    }

    fn union_index(&self, children: &[u32]) -> Option<Box<UnionIndex>> {
        let (bounded, unbounded): (Vec<u32>, Vec<u32>) = children
            .iter()
            .partition(|&&c| self.nodes[c as usize].bounds.is_bounded());
        if bounded.len() < bvh::MIN_CHILDREN {
            return None;
        }
        let items: Vec<(u32, Aabb)> = bounded
            .iter()
            .map(|&c| (c, self.nodes[c as usize].bounds))
            .collect();
        Some(Box::new(UnionIndex {
            bvh: Bvh::build(&items),
            unbounded,
        }))
    }

    fn add_node(&mut self, node: Node) -> u32 {
        self.nodes.push(node);
        self.nodes.len() as u32 - 1
    }

    /// The world box of everything (EMPTY for an empty tree).
    pub fn bounds(&self) -> Aabb {
        self.root
            .map_or(Aabb::EMPTY, |r| self.nodes[r as usize].bounds)
    }

    /// The spans of `node` along `ray`. The list agrees with the true solid
    /// on the open range (tmin, tmax); outside it, it may hold anything.
    pub fn spans(&self, node: u32, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> SpanList {
        let n = &self.nodes[node as usize];
        if n.bounds.is_bounded() {
            st.bound_tests += 1;
            if !n.bounds.hit(ray, tmin, tmax) {
                st.bound_culled += 1;
                return SpanList::new();
            }
        }
        self.spans_within(node, ray, tmin, tmax, st)
    }

    /// [`Csg::spans`] for a node whose box the caller has already found the
    /// ray to meet.
    fn spans_within(&self, node: u32, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> SpanList {
        let n = &self.nodes[node as usize];
        let out = match &n.kind {
            NodeKind::Leaf(p) => self.prim_spans(*p, ray, st),
            NodeKind::Union(ch) => {
                let mut acc = SpanList::new();
                let mut hit: SmallVec<[u32; 32]> = SmallVec::new();
                let ch: &[u32] = match &n.index {
                    Some(ix) => {
                        hit.extend_from_slice(&ix.unbounded);
                        ix.bvh.visit(ray, tmin, tmax, st, |c| hit.push(c));
                        &hit
                    }
                    None => ch,
                };
                for &c in ch {
                    let s = self.spans(c, ray, tmin, tmax, st);
                    union_into(&mut acc, s, ray);
                }
                acc
            }
            NodeKind::Intersection(ch) | NodeKind::Difference(ch) => {
                let op = if matches!(n.kind, NodeKind::Intersection(_)) {
                    Op::Intersection
                } else {
                    Op::Difference
                };
                let mut acc = self.spans(ch[0], ray, tmin, tmax, st);
                for &c in &ch[1..] {
                    if acc.is_empty() {
                        break;
                    }
                    // Later children matter only where the result may be.
                    let lo = tmin.max(acc[0].enter.t);
                    let hi = tmax.min(acc[acc.len() - 1].exit.t);
                    let s = self.spans(c, ray, lo, hi, st);
                    if s.is_empty() && op == Op::Difference {
                        continue;
                    }
                    acc = combine(op, &acc, &s, ray.origin.abs().max_element());
                }
                acc
            }
        };
        st.max_spans = st.max_spans.max(out.len() as u64);
        if out.spilled() {
            st.span_spills += 1;
        }
        out
    }

    fn prim_spans(&self, id: u32, ray: &Ray, st: &mut Stats) -> SpanList {
        st.primitive_tests += 1;
        let p = &self.prims[id as usize];
        let (o, d) = p.xf.ray_to_object(ray);
        let mut out = SpanList::new();
        p.shape.spans(o, d, &mut |(t0, p0, t1, p1)| {
            let b = |t, part| Boundary {
                t,
                prim: id,
                part,
                flip: false,
            };
            out.push(Span {
                enter: b(t0, p0),
                exit: b(t1, p1),
            })
        });
        out
    }

    /// The first surface boundary with `tmin < t < tmax`, if any.
    pub fn first_boundary(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
    ) -> Option<Boundary> {
        let root = self.root?;
        let list = match &self.nodes[root as usize].kind {
            NodeKind::Union(ch) => self.union_first(root, ch, ray, tmin, tmax, st),
            _ => self.spans(root, ray, tmin, tmax, st),
        };
        first_surface(&list, tmin).filter(|b| b.t < tmax)
    }

    /// A union's spans, good up to its first boundary after `tmin`.
    ///
    /// Children are taken in the order the ray enters their boxes; once the
    /// next box begins beyond the first boundary found, no child left can
    /// change the result before that boundary, and the walk stops.
    fn union_first(
        &self,
        node: u32,
        ch: &[u32],
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
    ) -> SpanList {
        let n = &self.nodes[node as usize];
        let scale = ray.origin.abs().max_element();
        // Every child reaching `add` has had its box tested already.
        let add = |acc: &mut SpanList, c, st: &mut Stats| {
            let s = self.spans_within(c, ray, tmin, tmax, st);
            union_into(acc, s, ray);
        };
        // A child whose box begins at the first boundary may touch it and
        // merge it away (a part standing on a floor), and boundaries within
        // the coincidence bound are one: only boxes beyond that are cut.
        let cut = |acc: &SpanList| {
            first_surface(acc, tmin).map_or(f64::INFINITY, |b| b.t + 2.0 * coincidence(b.t, scale))
        };
        // Best first over the hierarchy pays only for wide unions: measured
        // at 640×480 with one thread, a 12-torus union renders in 0.61 s by
        // sorting and 0.82 s best first, a Menger sponge of 8000 cubes in
        // 0.58 s by sorting and 0.40 s best first.
        if let Some(ix) = n.index.as_ref().filter(|_| ch.len() > BEST_FIRST_MIN) {
            let mut acc = SpanList::new();
            for &c in &ix.unbounded {
                add(&mut acc, c, st);
            }
            ix.bvh.visit_near_first(ray, tmin, tmax, st, |c, st| {
                add(&mut acc, c, st);
                cut(&acc)
            });
            return acc;
        }
        let mut order: SmallVec<[(f64, u32); 32]> = SmallVec::new();
        for &c in ch {
            let b = &self.nodes[c as usize].bounds;
            if !b.is_bounded() {
                order.push((tmin, c));
                continue;
            }
            st.bound_tests += 1;
            match b.entry(ray, tmin, tmax) {
                Some(t) => order.push((t, c)),
                None => st.bound_culled += 1,
            }
        }
        order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut acc = SpanList::new();
        for (entry, c) in order {
            if entry > cut(&acc) {
                break;
            }
            add(&mut acc, c, st);
        }
        acc
    }

    /// The first surface the ray hits in (tmin, tmax), with its normal.
    pub fn first_hit(&self, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> Option<SurfaceHit> {
        let b = self.first_boundary(ray, tmin, tmax, st)?;
        Some(self.surface(ray, &b, st))
    }

    /// Whether anything lies on the ray in (tmin, tmax).
    pub fn occluded(&self, ray: &Ray, tmin: f64, tmax: f64, st: &mut Stats) -> bool {
        self.first_boundary(ray, tmin, tmax, st).is_some()
    }

    /// Point and unit outward normal of a boundary found along `ray`.
    pub fn surface(&self, ray: &Ray, b: &Boundary, st: &mut Stats) -> SurfaceHit {
        st.normals_computed += 1;
        let p = &self.prims[b.prim as usize];
        let (o, d) = p.xf.ray_to_object(ray);
        let n_obj = p.shape.normal(o + b.t * d, b.part);
        let n = p.xf.normal_to_world(n_obj);
        SurfaceHit {
            t: b.t,
            point: ray.at(b.t),
            normal: if b.flip { -n } else { n },
            prim: b.prim,
        }
    }

    /// Whether a world point is inside the solid (boundaries count as in).
    pub fn contains(&self, node: u32, p: DVec3) -> bool {
        match &self.nodes[node as usize].kind {
            NodeKind::Leaf(i) => {
                let prim = &self.prims[*i as usize];
                prim.shape.contains(prim.xf.point_to_object(p))
            }
            NodeKind::Union(ch) => ch.iter().any(|&c| self.contains(c, p)),
            NodeKind::Intersection(ch) => ch.iter().all(|&c| self.contains(c, p)),
            NodeKind::Difference(ch) => {
                self.contains(ch[0], p) && !ch[1..].iter().any(|&c| self.contains(c, p))
            }
        }
    }
}

/// From how many children a union's first-hit query walks its hierarchy
/// best first instead of sorting every child the ray meets.
pub const BEST_FIRST_MIN: usize = 64;

/// The first real surface crossing after `tmin` in a list.
fn first_surface(list: &[Span], tmin: f64) -> Option<Boundary> {
    list.iter()
        .flat_map(|s| [s.enter, s.exit])
        .find(|b| b.t > tmin && b.is_surface())
}

/// `acc ← acc ∪ s`, in place, skipping the sweep when either side is empty
/// (lists are large values: every move is a copy).
fn union_into(acc: &mut SpanList, s: SpanList, ray: &Ray) {
    if s.is_empty() {
        return;
    }
    if acc.is_empty() {
        *acc = s;
    } else {
        *acc = combine(Op::Union, acc, &s, ray.origin.abs().max_element());
    }
}
