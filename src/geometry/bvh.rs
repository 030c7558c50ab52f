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

use crate::geometry::aabb::AabbPair;
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
    /// For each node, the boxes of its two children (inner) or items (a
    /// leaf of one or two; the second lane unused in a leaf of one), tested
    /// together. Larger leaves test their items one by one.
    pairs: Vec<AabbPair>,
    /// The most items a leaf holds.
    leaf: usize,
}

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
            pairs: Vec::new(),
            leaf,
        };
        bvh.nodes.push(BvhNode {
            bounds: Aabb::EMPTY,
            start: 0,
            count: 0,
        });
        bvh.split(0, &mut items);
        bvh.pairs = bvh
            .nodes
            .iter()
            .map(|n| {
                let (s, c) = (n.start as usize, n.count as usize);
                match c {
                    0 => AabbPair::new(&bvh.nodes[s].bounds, &bvh.nodes[s + 1].bounds),
                    1 => AabbPair::new(&bvh.item_bounds[s], &Aabb::EMPTY),
                    2 => AabbPair::new(&bvh.item_bounds[s], &bvh.item_bounds[s + 1]),
                    _ => AabbPair::new(&Aabb::EMPTY, &Aabb::EMPTY),
                }
            })
            .collect();
        bvh
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

    /// Calls `visit` for every child whose leaf box the ray meets in
    /// [tmin, tmax], in a fixed order (so results do not depend on threads).
    pub fn visit(
        &self,
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        mut visit: impl FnMut(u32),
    ) {
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            st.bound_tests += 1;
            if !n.bounds.hit(ray, tmin, tmax) {
                st.bound_culled += 1;
                continue;
            }
            if n.count > 0 {
                for &id in &self.items[n.start as usize..(n.start + n.count) as usize] {
                    visit(id);
                }
            } else {
                stack[top] = n.start + 1;
                stack[top + 1] = n.start;
                top += 2;
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
        // (entry, index, is an item): boxes still to open.
        let mut stack: SmallVec<[(f64, u32, bool); 64]> = SmallVec::new();
        let mut skipped: SmallVec<[(f64, u32, bool); 32]> = SmallVec::new();
        let test = |b: &Aabb, st: &mut Stats| {
            st.bound_tests += 1;
            let e = b.entry(ray, tmin, tmax);
            if e.is_none() {
                st.bound_culled += 1;
            }
            e
        };
        if let Some(e) = test(&self.nodes[0].bounds, st) {
            stack.push((e, 0, false));
        }
        loop {
            while let Some((e, i, item)) = stack.pop() {
                if e > cut {
                    skipped.push((e, i, item));
                    continue;
                }
                if item {
                    cut = visit(self.items[i as usize], st);
                    continue;
                }
                let n = &self.nodes[i as usize];
                if n.count > 2 {
                    // A large leaf: its items' boxes one by one, the
                    // farthest pushed first.
                    let mut found: SmallVec<[(f64, u32, bool); 16]> = SmallVec::new();
                    for k in n.start..n.start + n.count {
                        if let Some(e) = test(&self.item_bounds[k as usize], st) {
                            found.push((e, k, true));
                        }
                    }
                    found.sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(b.1.cmp(&a.1)));
                    for f in found {
                        if f.0 > cut {
                            skipped.push(f);
                        } else {
                            stack.push(f);
                        }
                    }
                    continue;
                }
                // Two boxes at most, tested together; then the farther is
                // pushed first so that the nearer pops first, and those
                // beginning beyond the cut go straight to the skipped.
                let entries = self.pairs[i as usize].entries(ray, tmin, tmax);
                let boxes = if n.count > 0 { n.count as usize } else { 2 };
                st.bound_tests += boxes as u64;
                let mut found = [(0.0, 0u32, false); 2];
                let mut m = 0;
                for (lane, e) in entries.into_iter().enumerate().take(boxes) {
                    let Some(e) = e else {
                        st.bound_culled += 1;
                        continue;
                    };
                    let k = n.start + lane as u32;
                    found[m] = if n.count > 0 {
                        (e, k, true)
                    } else {
                        // A leaf of one child has that child's box: it is
                        // the child, with no second test.
                        let child = &self.nodes[k as usize];
                        if child.count == 1 {
                            (e, child.start, true)
                        } else {
                            (e, k, false)
                        }
                    };
                    m += 1;
                }
                if m == 2 && (found[0].0, found[0].1) < (found[1].0, found[1].1) {
                    found.swap(0, 1);
                }
                for f in &found[..m] {
                    if f.0 > cut {
                        skipped.push(*f);
                    } else {
                        stack.push(*f);
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
    fn visits_every_child_whose_box_the_ray_meets_and_few_others() {
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
        // Every child the ray meets is visited; a leaf holds two, so a few
        // neighbours come along (their own boxes are tested after).
        for want in 30..40 {
            assert!(seen.contains(&want), "child {want} missed: {seen:?}");
        }
        assert!(seen.len() <= 20, "{} visited", seen.len());
        // Far fewer box tests than children.
        assert!(st.bound_tests < 60, "{} box tests", st.bound_tests);
    }
}
