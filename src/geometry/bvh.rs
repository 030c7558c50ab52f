//! A bounding volume hierarchy over boxed items named by ids — the children
//! of a wide CSG node (the 400 holes of a plate, the 1000 spheres of a
//! pile), a polygon's edges (a mesh has its own, `mesh_bvh`) — so that a ray looks only
//! at the items whose boxes it meets: O(log n + hits) box tests instead of
//! n.
//!
//! Built once, top down, splitting the items where the surface-area
//! heuristic is least, down to leaves of at most `leaf` items (a
//! parameter: 2 for a union's children, whose own tests are dear; more
//! where an item is cheap).

use crate::geometry::aabb::AabbLanes;
use crate::geometry::{Aabb, Ray};
use crate::stats::Stats;
use smallvec::SmallVec;

#[derive(Clone, Debug, PartialEq)]
struct BvhNode {
    bounds: Aabb,
    /// Leaf: `items[start..start + count]`; inner: children at `start` and
    /// `start + 1` in `nodes`, `count == 0`.
    start: u32,
    count: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Bvh {
    nodes: Vec<BvhNode>,
    /// Child node ids, in leaf order.
    items: Vec<u32>,
    /// Their boxes, in the same order.
    item_bounds: Vec<Aabb>,
    /// The most items a leaf holds.
    leaf: usize,
    /// The same tree collapsed to four boxes a node (two levels or more of
    /// the binary tree in one), for the nearest-first walk.
    wide: Vec<Wide>,
}

/// A node of [`Bvh::wide`]: up to four boxes tested at once, each an item's
/// own box ([`ITEM`] set in `child`: an index into `items`) or a node's.
#[derive(Clone, Debug, PartialEq)]
struct Wide {
    boxes: AabbLanes<4>,
    child: [u32; 4],
    lanes: u8,
}

/// Marks a [`Wide`] lane that is an item.
const ITEM: u32 = 1 << 31;

impl Bvh {
    /// A hierarchy over `(id, bounds)` pairs, all bounded, with at most
    /// `leaf` (≥ 1) items a leaf.
    pub fn build(children: &[(u32, Aabb)], leaf: usize) -> Bvh {
        Bvh::build_with(children.to_vec(), leaf)
    }

    fn build_with(mut items: Vec<(u32, Aabb)>, leaf: usize) -> Bvh {
        assert!(leaf >= 1, "a leaf holds at least one item");
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * items.len() / leaf + 1),
            items: Vec::with_capacity(items.len()),
            item_bounds: Vec::with_capacity(items.len()),
            leaf,
            wide: Vec::new(),
        };
        bvh.nodes.push(BvhNode {
            bounds: Aabb::EMPTY,
            start: 0,
            count: 0,
        });
        bvh.split(0, &mut items);
        bvh.collapse(0);
        bvh
    }

    /// The lanes a binary node opens into: its two children, or a leaf's
    /// items.
    fn opened(&self, at: usize) -> SmallVec<[u32; 4]> {
        let n = &self.nodes[at];
        if n.count == 0 {
            smallvec::smallvec![n.start, n.start + 1]
        } else {
            (n.start..n.start + n.count).map(|k| k | ITEM).collect()
        }
    }

    /// Adds the wide node over binary node `at` (and those under it);
    /// returns its index. The node starts from `at`'s own lanes and opens
    /// the largest binary node among them (by surface area, the first of
    /// equals) while what it opens into still fits in four lanes.
    fn collapse(&mut self, at: usize) -> u32 {
        let n = &self.nodes[at];
        if n.count > 4 {
            return self.range_node(n.start, n.count);
        }
        let mut lanes = self.opened(at);
        loop {
            let mut pick: Option<(usize, f64)> = None;
            for (j, &c) in lanes.iter().enumerate() {
                if c & ITEM != 0 {
                    continue;
                }
                let n = &self.nodes[c as usize];
                let size = if n.count == 0 { 2 } else { n.count as usize };
                let a = area(&n.bounds);
                if lanes.len() - 1 + size <= 4 && pick.map_or(true, |(_, b)| a > b) {
                    pick = Some((j, a));
                }
            }
            let Some((j, _)) = pick else { break };
            let open = self.opened(lanes[j] as usize);
            lanes.remove(j);
            for (k, c) in open.into_iter().enumerate() {
                lanes.insert(j + k, c);
            }
        }
        let me = self.wide.len();
        self.wide.push(Wide {
            boxes: AabbLanes::of(&[]),
            child: [u32::MAX; 4],
            lanes: lanes.len() as u8,
        });
        let mut boxes: SmallVec<[Aabb; 4]> = SmallVec::new();
        let mut child = [u32::MAX; 4];
        for (k, &c) in lanes.iter().enumerate() {
            if c & ITEM != 0 {
                boxes.push(self.item_bounds[(c & !ITEM) as usize]);
                child[k] = c;
            } else {
                boxes.push(self.nodes[c as usize].bounds);
                child[k] = self.collapse(c as usize);
            }
        }
        self.wide[me].boxes = AabbLanes::of(&boxes);
        self.wide[me].child = child;
        me as u32
    }

    /// Adds a wide node over items `start..start + count` of a leaf of
    /// more than four (a hierarchy built with larger leaves): four at most
    /// a node, in runs of the leaf's order; returns its index.
    fn range_node(&mut self, start: u32, count: u32) -> u32 {
        let me = self.wide.len();
        self.wide.push(Wide {
            boxes: AabbLanes::of(&[]),
            child: [u32::MAX; 4],
            lanes: 0,
        });
        let runs = count.min(4);
        let mut boxes: SmallVec<[Aabb; 4]> = SmallVec::new();
        let mut child = [u32::MAX; 4];
        let mut at = start;
        for k in 0..runs {
            // Runs of near-equal length, the longer first.
            let len = count / runs + u32::from(k < count % runs);
            let items = &self.item_bounds[at as usize..(at + len) as usize];
            boxes.push(items.iter().fold(Aabb::EMPTY, |a, b| a.union(b)));
            child[k as usize] = if len == 1 {
                at | ITEM
            } else {
                self.range_node(at, len)
            };
            at += len;
        }
        self.wide[me] = Wide {
            boxes: AabbLanes::of(&boxes),
            child,
            lanes: runs as u8,
        };
        me as u32
    }

    fn split(&mut self, at: usize, items: &mut [(u32, Aabb)]) {
        let bounds = items.iter().fold(Aabb::EMPTY, |a, (_, b)| a.union(b));
        self.nodes[at].bounds = bounds;
        if items.len() <= self.leaf {
            self.nodes[at].start = self.items.len() as u32;
            self.nodes[at].count = items.len() as u32;
            self.items.extend(items.iter().map(|(id, _)| *id));
            self.item_bounds.extend(items.iter().map(|(_, b)| *b));
            return;
        }
        let mid = sah_split(items);
        let left = self.nodes.len();
        for _ in 0..2 {
            self.nodes.push(BvhNode {
                bounds: Aabb::EMPTY,
                start: 0,
                count: 0,
            });
        }
        self.nodes[at].start = left as u32;
        let (a, b) = items.split_at_mut(mid);
        self.split(left, a);
        self.split(left + 1, b);
    }

    /// Calls `visit` for every item whose own box the ray meets in
    /// [tmin, tmax], in the hierarchy's leaf order (so results do not
    /// depend on threads): the wide nodes' four boxes at once, depth first,
    /// each node's lanes in order.
    pub fn visit(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        mut visit: impl FnMut(u32),
    ) {
        st.bound_tests += 1;
        if !self.nodes[0].bounds.hit(ray, tmin, tmax) {
            st.bound_culled += 1;
            return;
        }
        // Wide nodes and items still to open, the next on top.
        let mut stack: SmallVec<[u32; 64]> = SmallVec::new();
        stack.push(0);
        while let Some(c) = stack.pop() {
            if c & ITEM != 0 {
                visit(self.items[(c & !ITEM) as usize]);
                continue;
            }
            let n = &self.wide[c as usize];
            let (met, _) = n.boxes.entries_met_any(ray, tmin, tmax);
            let lanes = n.lanes as usize;
            st.bound_tests += lanes as u64;
            st.bound_culled += (lanes as u32 - (met & ((1 << lanes) - 1)).count_ones()) as u64;
            for k in (0..lanes).rev() {
                if met >> k & 1 != 0 {
                    stack.push(n.child[k]);
                }
            }
        }
    }
}

impl Bvh {
    /// Visits the children whose boxes the ray meets, nearer subtrees
    /// first, skipping every box that begins beyond the distance `visit`
    /// returns (the caller's cut-off; ∞ for none).
    ///
    /// Depth first, the nearer child of each node first. A box skipped for
    /// beginning beyond the cut is kept, and looked at again at the end
    /// should a later visit have moved the cut past it (a child that merges
    /// away the boundary that set the cut), so that on return every child
    /// whose box begins at or before the final cut has been visited.
    pub fn visit_near_first(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        mut visit: impl FnMut(u32, &mut Stats) -> f64,
    ) {
        let mut cut = f64::INFINITY;
        // (entry, wide node or item): boxes still to open.
        let mut stack: SmallVec<[(f64, u32); 64]> = SmallVec::new();
        let mut skipped: SmallVec<[(f64, u32); 32]> = SmallVec::new();
        st.bound_tests += 1;
        match self.nodes[0].bounds.entry(ray, tmin, tmax) {
            Some(e) => stack.push((e, 0)),
            None => {
                st.bound_culled += 1;
                return;
            }
        }
        loop {
            while let Some((e, c)) = stack.pop() {
                if e > cut {
                    skipped.push((e, c));
                    continue;
                }
                if c & ITEM != 0 {
                    cut = visit(self.items[(c & !ITEM) as usize], st);
                    continue;
                }
                // Four boxes at once; those met are pushed farthest first,
                // so that the nearest pops first (of equal entries, the
                // later lane), and those beginning beyond the cut go
                // straight to the skipped.
                let n = &self.wide[c as usize];
                let (met, t) = n.boxes.entries_met_any(ray, tmin, tmax);
                let lanes = n.lanes as usize;
                st.bound_tests += lanes as u64;
                let mut found = [(0.0, 0u32); 4];
                let mut m = 0;
                // (By index: the zipped form took 2 % more instructions.)
                #[allow(clippy::needless_range_loop)]
                for k in 0..lanes {
                    if met >> k & 1 != 0 {
                        found[m] = (t[k], n.child[k]);
                        m += 1;
                    }
                }
                st.bound_culled += (lanes - m) as u64;
                let found = &mut found[..m];
                // Insertion by entry, farthest first, stable.
                for i in 1..m {
                    let f = found[i];
                    let mut j = i;
                    while j > 0 && found[j - 1].0 < f.0 {
                        found[j] = found[j - 1];
                        j -= 1;
                    }
                    found[j] = f;
                }
                for &f in found.iter() {
                    if f.0 > cut {
                        skipped.push(f);
                    } else {
                        stack.push(f);
                    }
                }
            }
            // Whatever was skipped but now begins within the cut goes back.
            let before = skipped.len();
            let mut k = 0;
            while k < skipped.len() {
                if skipped[k].0 <= cut {
                    stack.push(skipped.swap_remove(k));
                } else {
                    k += 1;
                }
            }
            if skipped.len() == before {
                st.bound_culled += skipped.len() as u64;
                return;
            }
        }
    }
}

/// Surface area of a box: the chance a random ray that meets its parent
/// meets it is in proportion to it.
fn area(b: &Aabb) -> f64 {
    let e = b.max - b.min;
    e.x * e.y + e.y * e.z + e.z * e.x
}

/// Orders `items` and returns where to split them: along the axis and at
/// the place, in the order of box centres, that minimise the surface-area
/// heuristic `area(left)·n_left + area(right)·n_right`. Ties keep the
/// earlier axis and the more even split, so the tree depends only on the
/// input.
fn sah_split(items: &mut [(u32, Aabb)]) -> usize {
    let n = items.len();
    let by_centre = |axis: usize| {
        move |a: &(u32, Aabb), b: &(u32, Aabb)| {
            a.1.center()[axis]
                .total_cmp(&b.1.center()[axis])
                .then(a.0.cmp(&b.0))
        }
    };
    let mut best = (f64::INFINITY, 0usize, n / 2);
    let mut right = vec![0.0; n];
    for axis in 0..3 {
        items.sort_by(by_centre(axis));
        let mut acc = Aabb::EMPTY;
        for i in (1..n).rev() {
            acc = acc.union(&items[i].1);
            right[i] = area(&acc) * (n - i) as f64;
        }
        let mut acc = Aabb::EMPTY;
        for i in 1..n {
            acc = acc.union(&items[i - 1].1);
            let cost = area(&acc) * i as f64 + right[i];
            let even = (2 * i).abs_diff(n) < (2 * best.2).abs_diff(n);
            if cost < best.0 || (cost == best.0 && axis == best.1 && even) {
                best = (cost, axis, i);
            }
        }
    }
    let (_, axis, mid) = best;
    items.sort_by(by_centre(axis));
    mid
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn visits_exactly_the_children_whose_boxes_the_ray_meets() {
        // A 10 × 10 grid of unit boxes; a ray along row 3.
        let kids: Vec<(u32, Aabb)> = (0..100)
            .map(|i| {
                let p = DVec3::new((i % 10) as f64 * 2.0, (i / 10) as f64 * 2.0, 0.0);
                (i, Aabb::new(p, p + DVec3::ONE))
            })
            .collect();
        let bvh = Bvh::build(&kids, 2);
        let ray = Ray::new(DVec3::new(-5.0, 6.5, 0.5), DVec3::X);
        let mut seen = Vec::new();
        let mut st = Stats::default();
        bvh.visit(&ray, 0.0, f64::INFINITY, &mut st, |id| seen.push(id));
        // Exactly the children whose own boxes the ray meets (each lane of
        // a wide node is a child's box), each once.
        seen.sort_unstable();
        let met: Vec<u32> = kids
            .iter()
            .filter(|(_, b)| b.hit(&ray, 0.0, f64::INFINITY))
            .map(|&(id, _)| id)
            .collect();
        assert_eq!(seen, met);
        assert_eq!(met, (30..40).collect::<Vec<u32>>());
        // Fewer boxes tested (four lanes a wide node, each counted) than
        // the hundred a scan of the children would test.
        assert!(st.bound_tests < 70, "{} box tests", st.bound_tests);
    }

    #[test]
    fn the_nearest_first_walk_opens_every_box_that_begins_within_the_last_cut() {
        // Boxes of many sizes, some nested and some flat; rays from inside
        // and outside; a cut that moves both ways (down to the least exit
        // seen, then up past boxes already skipped).
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [1, 2, 3, 5, 8, 40, 300] {
            let kids: Vec<(u32, Aabb)> = (0..n)
                .map(|i| {
                    let c = DVec3::new(next(), next(), next()) * 20.0 - 10.0;
                    let mut e = DVec3::new(next(), next(), next()) * 3.0;
                    if i % 7 == 3 {
                        e.z = 0.0;
                    }
                    (i, Aabb::new(c - e, c + e))
                })
                .collect();
            let bvh = Bvh::build(&kids, 2);
            for r in 0..200 {
                let o = DVec3::new(next(), next(), next()) * 30.0 - 15.0;
                let d = DVec3::new(next(), next(), next()) - 0.5;
                let ray = Ray::new(o, d);
                let mut seen: Vec<u32> = Vec::new();
                let mut st = Stats::default();
                let mut last = f64::INFINITY;
                bvh.visit_near_first(&ray, 0.0, f64::INFINITY, &mut st, |id, _| {
                    assert!(!seen.contains(&id), "child {id} visited twice");
                    seen.push(id);
                    let b = &kids[id as usize].1;
                    let e = b.entry(&ray, 0.0, f64::INFINITY).unwrap();
                    last = if seen.len() % 3 == 2 && r % 2 == 0 {
                        e + 8.0
                    } else {
                        e + 0.5
                    };
                    last
                });
                for (id, b) in &kids {
                    if let Some(e) = b.entry(&ray, 0.0, f64::INFINITY) {
                        assert!(
                            e > last || seen.contains(id),
                            "child {id} (entry {e}) not visited, cut {last}, {n} children"
                        );
                    } else {
                        assert!(!seen.contains(id), "child {id} visited, its box missed");
                    }
                }
            }
        }
    }
}
