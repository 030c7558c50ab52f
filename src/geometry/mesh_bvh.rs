//! A mesh's own hierarchy: eight-wide nodes of `f32` boxes over ranges of
//! its triangles, with no box kept for a triangle (Wald, Benthin and
//! Boulos 2008's multi-branching BVH; the layout of Embree's `BVH8`).
//!
//! Built top down by binned SAH (16 bins along the widest spread of
//! triangle centres), each node taking the eight largest parts of up to
//! seven splits; the triangles are put in leaf order, so that a leaf is a
//! range of at most [`LEAF_MAX`] of them.
//!
//! **Conservative in `f32`.** A box never culls a triangle that the exact
//! `f64` test would cross:
//! - each box is its triangles' `f64` box rounded outward to `f32`;
//! - the line is first clipped, in `f64`, to the mesh's whole box and its
//!   origin moved to the middle of that piece (`o' = o + s·d`), so that
//!   every distance the test computes is at most `T`, about the box's
//!   size; its direction is scaled by a power of two (exact) to a largest
//!   component in [1, 2);
//! - `o'` goes to `f32` rounded up for one side of each slab and down for
//!   the other, by at least the rounding of `o + s·d`, so that each slab
//!   distance computed errs only by the rounding of one subtraction, one
//!   product and of `1/d`: at most 3.01·2⁻²⁴ of itself, hence (the
//!   distances being clipped to [−T, T]) at most 3.02·2⁻²⁴·T after the
//!   clip. A box is taken when `near ≤ far + ε` with `ε = 10·2⁻²⁴·T`;
//! - a direction component below 2⁻⁶⁰ of the largest is a slab parallel
//!   to the line: its `1/d` is +∞ and the origins are widened by the
//!   most the line moves along that axis within [−T, T], so that the
//!   slab passes exactly when the line's range there meets it;
//! - a `0·∞` NaN (an origin exactly on a plane of such a slab) constrains
//!   nothing: the running bounds are always the second operand of the
//!   select, which returns it on NaN.
//!
//! Mesh coordinates are limited to ±[`MAX_COORD`] so that no distance
//! overflows `f32` (the resolver refuses larger ones).

use super::Aabb;
use crate::stats::Stats;
use glam::DVec3;
use smallvec::SmallVec;
use std::mem::MaybeUninit;

/// The most triangles in a leaf (at most 8: the count is kept in 3 bits).
/// A node's parts of more than `SPLIT_ABOVE` are split while it has
/// lanes left; a part of three left when its eight lanes are taken is a
/// leaf, not a node of two leaves and six empty lanes. On the bench's
/// 1.3-million-triangle mesh (eight-wide, 2026-12-03): leaves of at most
/// 2, 3 or 4 took the same time (3.0, 3.2, 3.5 triangle tests and 9.2,
/// 9.0, 8.8 nodes a ray) with 229, 189 and 154 thousand nodes; three is
/// the middle.
pub const LEAF_MAX: usize = 3;
/// A part of a node with more triangles than this is split while the node
/// has lanes left (at two: 2.96 triangle tests a ray against 4.86 at
/// four with the four-wide nodes, and 15 % faster).
const SPLIT_ABOVE: usize = 2;

/// The largest mesh coordinate (2⁶⁰): a slab distance, at most 2⁶² over a
/// direction component of at least 2⁻⁶⁰, stays below `f32::MAX`.
pub const MAX_COORD: f64 = 1.152_921_504_606_847e18;

/// The first of `points` beyond ±[`MAX_COORD`] in some coordinate, if any.
pub fn too_far(points: &[DVec3]) -> Option<&DVec3> {
    points.iter().find(|p| p.abs().max_element() > MAX_COORD)
}

/// Children a node has: eight, as Embree's `BVH8` on a processor with
/// AVX. On the bench's mesh, against four: 9.2 nodes a ray instead of
/// 13.7 for the same 3.0 triangle tests, 7 to 10 % faster (a walk waits
/// on each node's load and its branches, not on its arithmetic).
const WIDTH: usize = 8;
const BINS: usize = 16;
/// From this depth of binary splits on, a node is halved at its median
/// (so that no mesh makes the tree, or a ray's stack, deeper than
/// `MEDIAN_FROM + 28` levels).
const MEDIAN_FROM: usize = 40;
/// The most entries a walk's stack holds: seven a level of the deepest
/// tree the build makes.
const STACK: usize = (WIDTH - 1) * (MEDIAN_FROM + 30) + 1;

/// A walk's stack: an array of [`STACK`] entries, never cleared (3.9 kB;
/// 1.7 kB to clear for each line took as long as a tenth of its walk).
struct Stack<T> {
    top: usize,
    at: [MaybeUninit<T>; STACK],
}

impl<T: Copy> Stack<T> {
    #[inline(always)]
    fn new() -> Self {
        Stack {
            top: 0,
            at: [MaybeUninit::uninit(); STACK],
        }
    }

    #[inline(always)]
    fn push(&mut self, x: T) {
        self.at[self.top] = MaybeUninit::new(x);
        self.top += 1;
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<T> {
        if self.top == 0 {
            return None;
        }
        self.top -= 1;
        // SAFETY: entries below `top` were each written by `push`.
        Some(unsafe { self.at[self.top].assume_init() })
    }
}

const LEAF_BIT: u32 = 1 << 31;

/// A leaf child's code (`LEAF_BIT`, the count less one in bits 28–30, the
/// first triangle below).
fn leaf_code(first: usize, count: usize) -> u32 {
    LEAF_BIT | (((count - 1) as u32) << 28) | first as u32
}

/// A leaf child's (first triangle, count).
#[inline]
fn leaf_range(c: u32) -> (u32, u32) {
    (c & 0x0fff_ffff, ((c >> 28) & 7) + 1)
}
const EMPTY_LANE: u32 = u32::MAX;
/// Below this fraction of the largest component, a direction component
/// makes a parallel slab.
const PARALLEL: f64 = 8.673_617_379_884_035e-19; // 2⁻⁶⁰
const U32: f64 = 5.960_464_477_539_063e-8; // 2⁻²⁴

/// Eight children's boxes, axis by axis and lane by lane, and what each
/// child is: an inner node's index, a leaf's range (`LEAF_BIT`, the count
/// less one in bits 28–30, the first triangle below), or `EMPTY_LANE`
/// (whose box is empty: +∞ below, −∞ above, never met).
#[derive(Clone, Debug, PartialEq)]
#[repr(C, align(16))]
struct MeshNode {
    /// The boxes' lower planes along x, y, z, then their upper planes.
    b: [[f32; WIDTH]; 6],
    child: [u32; WIDTH],
}

impl MeshNode {
    /// The near and the far planes of the boxes along axis `a` for a line
    /// whose direction has the signs `OCTANT` (bit a set: the near plane is
    /// the upper one).
    #[inline(always)]
    fn planes<const OCTANT: u8>(&self, a: usize) -> (&[f32; WIDTH], &[f32; WIDTH]) {
        if OCTANT >> a & 1 == 1 {
            (&self.b[a + 3], &self.b[a])
        } else {
            (&self.b[a], &self.b[a + 3])
        }
    }
}

/// Whether this processor has AVX ([`super::aabb::has_avx`], which the
/// union's box lanes ask too) and `popcnt` (asked once: the answers are
/// kept).
#[cfg(target_arch = "x86_64")]
#[inline]
fn has_avx() -> bool {
    super::aabb::has_avx() && std::arch::is_x86_feature_detected!("popcnt")
}

/// How many bits of a four-bit mask are set (a table: `count_ones` is a
/// dozen instructions on a processor without `popcnt`, such as the
/// x86-64 baseline this crate is built for).
const BITS4: [u32; 16] = [0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4];

const EMPTY_NODE: MeshNode = MeshNode {
    b: [
        [f32::INFINITY; WIDTH],
        [f32::INFINITY; WIDTH],
        [f32::INFINITY; WIDTH],
        [f32::NEG_INFINITY; WIDTH],
        [f32::NEG_INFINITY; WIDTH],
        [f32::NEG_INFINITY; WIDTH],
    ],
    child: [EMPTY_LANE; WIDTH],
};

#[derive(Clone, Debug, PartialEq)]
pub struct MeshBvh {
    nodes: Vec<MeshNode>,
}

/// A triangle's box while building.
#[derive(Clone, Copy)]
struct Item {
    lo: [f32; 3],
    hi: [f32; 3],
    id: u32,
    /// Its bin in the split being made.
    bin: u8,
}

#[derive(Clone, Copy)]
struct Box32 {
    lo: [f32; 3],
    hi: [f32; 3],
}

const EMPTY_BOX: Box32 = Box32 {
    lo: [f32::INFINITY; 3],
    hi: [f32::NEG_INFINITY; 3],
};

impl Box32 {
    #[inline]
    fn grow(&mut self, it: &Item) {
        for a in 0..3 {
            self.lo[a] = lesser(self.lo[a], it.lo[a]);
            self.hi[a] = greater(self.hi[a], it.hi[a]);
        }
    }

    fn join(&mut self, o: &Box32) {
        for a in 0..3 {
            self.lo[a] = lesser(self.lo[a], o.lo[a]);
            self.hi[a] = greater(self.hi[a], o.hi[a]);
        }
    }

    /// Grows the box to hold twice the item's centre ([`centre`]).
    #[inline]
    fn grow_centre(&mut self, it: &Item) {
        for a in 0..3 {
            let c = centre(it, a);
            self.lo[a] = lesser(self.lo[a], c);
            self.hi[a] = greater(self.hi[a], c);
        }
    }

    fn centres(items: &[Item]) -> Box32 {
        let mut b = EMPTY_BOX;
        for it in items {
            b.grow_centre(it);
        }
        b
    }

    fn of(items: &[Item]) -> Box32 {
        let mut b = EMPTY_BOX;
        for it in items {
            b.grow(it);
        }
        b
    }

    /// Half the surface area (the SAH's measure), 0 for an empty box.
    fn area(&self) -> f64 {
        // Written out, not through `[_; 3]::map` (the SAH weighs about 30
        // boxes a split: a tenth of the build's instructions).
        let e = |a: usize| (self.hi[a] as f64 - self.lo[a] as f64).max(0.0);
        let (x, y, z) = (e(0), e(1), e(2));
        x * y + y * z + z * x
    }
}

/// The lesser and the greater of two values that are never NaN (box
/// planes of bounded coordinates), as one `minss`/`maxss` each.
#[inline(always)]
fn lesser(a: f32, b: f32) -> f32 {
    if b < a {
        b
    } else {
        a
    }
}

#[inline(always)]
fn greater(a: f32, b: f32) -> f32 {
    if b > a {
        b
    } else {
        a
    }
}

/// Twice a box's centre along `a` (the order of centres is all binning uses).
#[inline]
fn centre(it: &Item, a: usize) -> f32 {
    it.lo[a] + it.hi[a]
}

/// The least `f32` above `x` (finite `x`; `f32::next_up`, which is newer
/// than this crate's minimum Rust).
fn step_up(x: f32) -> f32 {
    if x.is_nan() || x == f32::INFINITY {
        x
    } else if x == 0.0 {
        f32::from_bits(1)
    } else if x > 0.0 {
        f32::from_bits(x.to_bits() + 1)
    } else {
        f32::from_bits(x.to_bits() - 1)
    }
}

/// `x` rounded to an `f32` at most `x`.
#[inline]
pub fn down32(x: f64) -> f32 {
    let r = x as f32;
    if r as f64 > x {
        -step_up(-r)
    } else {
        r
    }
}

/// `x` rounded to an `f32` at least `x`.
#[inline]
pub fn up32(x: f64) -> f32 {
    let r = x as f32;
    if (r as f64) < x {
        step_up(r)
    } else {
        r
    }
}

/// An `f32` at least `x` (finite or infinite, not NaN), at most three
/// steps above it: `x` moved up by more than half an `f32` step before rounding
/// to nearest, with no branch (a ray's set-up rounds a dozen values, each
/// way at random; [`up32`]'s test is a branch mispredicted half the time).
#[inline(always)]
fn above32(x: f64) -> f32 {
    (x + (x.abs() * TWO_POW_M23 + F32_TINY)) as f32
}

/// An `f32` at most `x`, at most three steps below it ([`above32`]).
#[inline(always)]
fn below32(x: f64) -> f32 {
    (x - (x.abs() * TWO_POW_M23 + F32_TINY)) as f32
}

/// The greatest power of two at most `m` (positive and finite, subnormal
/// too), exactly.
pub(crate) fn pow2_floor(m: f64) -> f64 {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    if m >= f64::MIN_POSITIVE {
        f64::from_bits(m.to_bits() & EXPONENT)
    } else {
        // Through 2^64 and back (exact scalings of a power of two): 2^e by
        // `powi` is 1 / 2^-e, zero for e below -1023.
        f64::from_bits((m * 18_446_744_073_709_551_616.0).to_bits() & EXPONENT)
            * 5.421_010_862_427_522e-20
    }
}

/// 2⁻²³: twice the largest relative rounding of an `f32` (round to
/// nearest moves a value by at most 2⁻²⁴ of itself, or by 2⁻¹⁵⁰ below the
/// normal range).
const TWO_POW_M23: f64 = 1.192_092_895_507_812_5e-7;
/// 2⁻¹⁴⁹, the least `f32` step.
const F32_TINY: f64 = 1.401_298_464_324_817e-45;

/// `$body` with `$o` a constant equal to `$octant` (0 to 7): a walk
/// compiled for each octant of directions, so that which plane of each
/// slab is the near one is known when it is compiled.
macro_rules! by_octant {
    ($octant:expr, $o:ident => $body:expr) => {
        match $octant {
            0 => {
                const $o: u8 = 0;
                $body
            }
            1 => {
                const $o: u8 = 1;
                $body
            }
            2 => {
                const $o: u8 = 2;
                $body
            }
            3 => {
                const $o: u8 = 3;
                $body
            }
            4 => {
                const $o: u8 = 4;
                $body
            }
            5 => {
                const $o: u8 = 5;
                $body
            }
            6 => {
                const $o: u8 = 6;
                $body
            }
            _ => {
                const $o: u8 = 7;
                $body
            }
        }
    };
}

impl MeshBvh {
    /// The hierarchy of `tris` over `verts` (at most 2²⁸ triangles, every
    /// coordinate within ±[`MAX_COORD`]), and the order to put the
    /// triangles in: `order[k]` is the triangle that goes to place `k`,
    /// leaves naming ranges of places.
    pub fn build(verts: &[DVec3], tris: &[[u32; 3]]) -> (MeshBvh, Vec<u32>) {
        let mut items: Vec<Item> = tris
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let p = t.map(|k| verts[k as usize]);
                let lo = p[0].min(p[1]).min(p[2]);
                let hi = p[0].max(p[1]).max(p[2]);
                Item {
                    lo: [down32(lo.x), down32(lo.y), down32(lo.z)],
                    hi: [up32(hi.x), up32(hi.y), up32(hi.z)],
                    id: i as u32,
                    bin: 0,
                }
            })
            .collect();
        let mut bvh = MeshBvh {
            // About one node for seven triangles: room for one for four,
            // reserved but not touched, so that the vector never grows by
            // a copy (which holds both at the peak); the rest handed back.
            nodes: Vec::with_capacity(items.len() / 4 + 1),
        };
        if !items.is_empty() {
            let all = Box32::of(&items);
            let centres = Box32::centres(&items);
            bvh.node(&mut items, 0, [all, centres], 0);
        }
        bvh.nodes.shrink_to_fit();
        let order = items.iter().map(|it| it.id).collect();
        (bvh, order)
    }

    /// Builds the node over `items` (places `base..`, their box `bounds`
    /// and their centres' box `centres`) at a binary depth of `depth`;
    /// returns its index.
    fn node(
        &mut self,
        items: &mut [Item],
        base: usize,
        [bounds, centres]: [Box32; 2],
        depth: usize,
    ) -> u32 {
        let me = self.nodes.len();
        self.nodes.push(EMPTY_NODE);
        let mut parts: SmallVec<[SplitPart; WIDTH]> = SmallVec::new();
        parts.push((0, items.len(), bounds, centres, depth));
        while parts.len() < WIDTH {
            // The largest part that is too big for a leaf is split.
            let mut pick: Option<(usize, f64)> = None;
            for (j, p) in parts.iter().enumerate() {
                if p.1 - p.0 > SPLIT_ABOVE && pick.map_or(true, |(_, a)| p.2.area() > a) {
                    pick = Some((j, p.2.area()));
                }
            }
            let Some((j, _)) = pick else { break };
            let (s, e, _, cb, d) = parts[j];
            let cut = split(&mut items[s..e], d, &cb);
            let mid = s + cut.mid;
            parts[j] = (s, mid, cut.boxes[0], cut.centres[0], d + 1);
            parts.insert(j + 1, (mid, e, cut.boxes[1], cut.centres[1], d + 1));
        }
        let mut n = EMPTY_NODE;
        for (lane, &(s, e, b, cb, d)) in parts.iter().enumerate() {
            for a in 0..3 {
                n.b[a][lane] = b.lo[a];
                n.b[a + 3][lane] = b.hi[a];
            }
            n.child[lane] = if e - s <= LEAF_MAX {
                leaf_code(base + s, e - s)
            } else {
                self.node(&mut items[s..e], base + s, [b, cb], d)
            };
        }
        self.nodes[me] = n;
        me as u32
    }

    /// The line set up for the walk, if there is anything to walk: a
    /// hierarchy with nodes, and a piece of the line in `root`.
    fn line(&self, root: &Aabb, o: DVec3, d: DVec3, tmin: f64, tmax: f64) -> Option<Line32> {
        if self.nodes.is_empty() {
            return None;
        }
        Line32::new(root, o, d, tmin, tmax)
    }

    /// Calls `leaf(first, count)` for every leaf whose box the line `o +
    /// t·d` may meet for some t in [tmin, tmax] within `root` (the mesh's
    /// box), in a fixed order, until it returns `true`.
    #[allow(clippy::too_many_arguments)]
    pub fn visit(
        &self,
        root: &Aabb,
        o: DVec3,
        d: DVec3,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        leaf: impl FnMut(u32, u32) -> bool,
    ) {
        let Some(l) = self.line(root, o, d, tmin, tmax) else {
            return;
        };
        by_octant!(l.octant, O => self.every::<O>(&l, st, leaf))
    }

    /// [`visit`](Self::visit) for a line whose direction has the signs
    /// `OCTANT` (bit a set: negative along axis a).
    #[inline(always)]
    fn every<const OCTANT: u8>(
        &self,
        l: &Line32,
        st: &mut Stats,
        mut leaf: impl FnMut(u32, u32) -> bool,
    ) {
        let mut stack = Stack::new();
        stack.push(0);
        while let Some(at) = stack.pop() {
            let n = &self.nodes[at as usize];
            let (near, _) = l.test::<OCTANT>(n, l.tmax);
            for (lane, &c) in n.child.iter().enumerate() {
                if c == EMPTY_LANE {
                    continue;
                }
                st.bound_tests += 1;
                if near & (1 << lane) == 0 {
                    st.bound_culled += 1;
                } else if c & LEAF_BIT != 0 {
                    let (first, count) = leaf_range(c);
                    if leaf(first, count) {
                        return;
                    }
                } else {
                    stack.push(c);
                }
            }
        }
    }

    /// Calls `leaf(first, count)` for the leaves whose boxes the line may
    /// meet within [tmin, tmax] and `root`, nearest box first, skipping
    /// every box that begins beyond the cut `leaf` returns (the nearest
    /// crossing so far; ∞ for none). Returns whether the line may meet
    /// `root` at or before `tmin` too (the same outward-rounded slab test
    /// over (−∞, tmin]; `false` when it meets nothing in [tmin, tmax]).
    #[allow(clippy::too_many_arguments)]
    pub fn visit_near_first(
        &self,
        root: &Aabb,
        o: DVec3,
        d: DVec3,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        leaf: impl FnMut(u32, u32) -> f64,
    ) -> bool {
        let Some(l) = self.line(root, o, d, tmin, tmax) else {
            return false;
        };
        #[cfg(target_arch = "x86_64")]
        if has_avx() {
            // SAFETY: the processor has AVX and popcnt.
            by_octant!(l.octant, O => unsafe { self.near_first_avx::<O>(&l, st, leaf) });
            return l.before;
        }
        by_octant!(l.octant, O => self.near_first::<O, false>(&l, st, leaf));
        l.before
    }

    /// [`near_first`](Self::near_first) compiled for AVX (and `popcnt`,
    /// which every processor with AVX has), its node test eight lanes at
    /// once.
    ///
    /// # Safety
    /// The processor must have AVX and `popcnt` ([`has_avx`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,popcnt")]
    unsafe fn near_first_avx<const OCTANT: u8>(
        &self,
        l: &Line32,
        st: &mut Stats,
        leaf: impl FnMut(u32, u32) -> f64,
    ) {
        self.near_first::<OCTANT, true>(l, st, leaf)
    }

    /// [`visit_near_first`](Self::visit_near_first) for a line whose
    /// direction has the signs `OCTANT` (bit a set: negative along axis a),
    /// its node test in AVX registers if `AVX` (only where inlined into
    /// [`near_first_avx`](Self::near_first_avx)).
    #[inline(always)]
    fn near_first<const OCTANT: u8, const AVX: bool>(
        &self,
        l: &Line32,
        st: &mut Stats,
        mut leaf: impl FnMut(u32, u32) -> f64,
    ) {
        let mut cut = l.tmax;
        let mut stack = Stack::new();
        // Nodes tested (four boxes each, empty lanes included), boxes met,
        // and pushed boxes dropped for beginning beyond the cut.
        let (mut nodes, mut met, mut dropped) = (0u64, 0u64, 0u64);
        // The node or leaf opened next; its box begins before the cut.
        let mut cur = 0u32;
        'walk: loop {
            // Down from `cur` along the nearest box met, the others pushed.
            loop {
                if cur & LEAF_BIT != 0 {
                    let (first, count) = leaf_range(cur);
                    let best = leaf(first, count);
                    if best < f64::INFINITY {
                        cut = cut.min(l.local_up(best));
                    }
                    break;
                }
                let n = &self.nodes[cur as usize];
                let (mut mask, tn) = l.test_with::<OCTANT, AVX>(n, cut);
                nodes += 1;
                met += u64::from(if AVX {
                    mask.count_ones()
                } else {
                    BITS4[(mask & 15) as usize] + BITS4[(mask >> 4) as usize]
                });
                if mask == 0 {
                    break;
                }
                let a = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if mask == 0 {
                    cur = n.child[a];
                    continue;
                }
                let b = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if mask == 0 {
                    // Two met: the nearer opened, the other pushed (ties
                    // by lane: one order, whatever the threads).
                    let (near, far) = if tn[b] < tn[a] { (b, a) } else { (a, b) };
                    stack.push((n.child[far], tn[far]));
                    cur = n.child[near];
                    continue;
                }
                // Three or four: sorted by entry (ties by lane), the nearest
                // opened, the others pushed farthest first.
                let mut found = [(0f32, 0u32); WIDTH];
                found[0] = (tn[a], n.child[a]);
                found[1] = (tn[b], n.child[b]);
                let mut k = 2;
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    found[k] = (tn[lane], n.child[lane]);
                    k += 1;
                }
                // Insertion by entry, stable: lanes in order among ties.
                for i in 1..k {
                    let f = found[i];
                    let mut j = i;
                    while j > 0 && found[j - 1].0 > f.0 {
                        found[j] = found[j - 1];
                        j -= 1;
                    }
                    found[j] = f;
                }
                for j in (1..k).rev() {
                    stack.push((found[j].1, found[j].0));
                }
                cur = found[0].1;
            }
            // Up: the nearest pushed box that still begins before the cut.
            loop {
                let Some((c, entry)) = stack.pop() else {
                    break 'walk;
                };
                if entry <= cut + l.eps {
                    cur = c;
                    continue 'walk;
                }
                dropped += 1;
            }
        }
        let tests = WIDTH as u64 * nodes;
        st.bound_tests += tests;
        st.bound_culled += tests - met + dropped;
    }

    /// How many nodes the hierarchy has (for its memory).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
}

/// Splits `items` in two non-empty parts and returns the size of the
/// first and the boxes of both: at the binned SAH's best plane across the widest spread of
/// centres, or at the median from binary depth [`MEDIAN_FROM`] on or when
/// every centre is in one place.
fn split(items: &mut [Item], depth: usize, centres: &Box32) -> Split {
    let n = items.len();
    let (cmin, cmax) = (centres.lo, centres.hi);
    let ext = [0, 1, 2].map(|a| cmax[a] - cmin[a]);
    let axis = (0..3).fold(0, |w, a| if ext[a] > ext[w] { a } else { w });
    if ext[axis] <= 0.0 || !ext[axis].is_finite() || depth >= MEDIAN_FROM {
        let mid = n / 2;
        items.select_nth_unstable_by(mid, |p, q| {
            centre(p, axis)
                .total_cmp(&centre(q, axis))
                .then(p.id.cmp(&q.id))
        });
        let (l, r) = items.split_at(mid);
        return Split {
            mid,
            boxes: [Box32::of(l), Box32::of(r)],
            centres: [Box32::centres(l), Box32::centres(r)],
        };
    }
    // Only along the widest spread (along all three: 5 % fewer boxes a
    // ray, for a build 60 % slower).
    let k = BINS as f32 / ext[axis];
    let bin = |it: &Item| (((centre(it, axis) - cmin[axis]) * k) as usize).min(BINS - 1);
    let mut count = [0usize; BINS];
    let mut boxes = [EMPTY_BOX; BINS];
    let mut cboxes = [EMPTY_BOX; BINS];
    // Each item's bin, kept for the partition (computed once).
    for it in items.iter_mut() {
        let b = bin(it);
        count[b] += 1;
        boxes[b].grow(it);
        cboxes[b].grow_centre(it);
        it.bin = b as u8;
    }
    // The boxes of bins i.. and their SAH weight.
    let mut right = [(EMPTY_BOX, 0.0f64); BINS];
    let (mut acc, mut c) = (EMPTY_BOX, 0);
    for i in (1..BINS).rev() {
        acc.join(&boxes[i]);
        c += count[i];
        right[i] = (acc, acc.area() * c as f64);
    }
    // (cost, first bin on the right, box on the left). The centres span at
    // least two bins (the least in the first, the greatest in the last),
    // so a plane is found.
    let mut best = (f64::INFINITY, 0, EMPTY_BOX);
    let (mut acc, mut c) = (EMPTY_BOX, 0);
    for i in 1..BINS {
        acc.join(&boxes[i - 1]);
        c += count[i - 1];
        if c == 0 || c == n {
            continue;
        }
        let cost = acc.area() * c as f64 + right[i].1;
        if cost < best.0 {
            best = (cost, i, acc);
        }
    }
    let (_, at, left) = best;
    // Partitioned in place; each side's centres (the next splits' spread)
    // are its bins' centres.
    let mut i = 0;
    for j in 0..n {
        if usize::from(items[j].bin) < at {
            items.swap(i, j);
            i += 1;
        }
    }
    let mut cs = [EMPTY_BOX; 2];
    for (b, cb) in cboxes.iter().enumerate() {
        cs[usize::from(b >= at)].join(cb);
    }
    Split {
        mid: i,
        boxes: [left, right[at].0],
        centres: cs,
    }
}

/// A node's part while it is built: (start, end, box, centres' box, binary
/// depth), in place order.
type SplitPart = (usize, usize, Box32, Box32, usize);

/// Where [`split`] cut, and the boxes and the centres' boxes of each side.
struct Split {
    mid: usize,
    boxes: [Box32; 2],
    centres: [Box32; 2],
}

/// Where the line `o + t·d` may enter the bounded box `b` and leave it,
/// over all t: the greatest of its slabs' near distances and the least of
/// their far ones. Only the axes not `parallel` constrain it: along those
/// a rounding of the line's position is more than its motion, and the
/// walk's own tests bound the position instead (see [`Line32::new`]).
/// Divided, not multiplied by 1 / d: a component below 2⁻¹⁰²⁴ has no
/// finite inverse.
fn slabs(b: &Aabb, o: DVec3, d: DVec3, parallel: [bool; 3]) -> (f64, f64) {
    let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
    for a in 0..3 {
        let x = (b.min[a] - o[a]) / d[a];
        let y = (b.max[a] - o[a]) / d[a];
        // Plain compares (no NaN rules of `f64::min`): both are numbers
        // when `ok` (an overflow to ±∞ is a number).
        let ok = !(x.is_nan() | y.is_nan() | parallel[a]);
        let (n, f) = if x < y { (x, y) } else { (y, x) };
        near = if ok & (n > near) { n } else { near };
        far = if ok & (f < far) { f } else { far };
    }
    (near, far)
}

/// The piece `[lo, hi]` of `[tmin, tmax]` within [`slabs`]' `(near,
/// far)`, widened for rounding; `None` if there is none.
fn clip((near, far): (f64, f64), tmin: f64, tmax: f64) -> Option<(f64, f64)> {
    let lo = tmin.max(near);
    let hi = tmax.min(far);
    const W: f64 = 8.0 * f64::EPSILON;
    let (lo, hi) = (lo - W * lo.abs(), hi + W * hi.abs());
    (lo <= hi && lo.is_finite() && hi.is_finite()).then_some((lo, hi))
}

/// A line set up for the `f32` box tests (see the module's notes).
struct Line32 {
    /// The origin for each axis's near plane and far plane.
    on: [f32; 3],
    of: [f32; 3],
    inv: [f32; 3],
    /// The direction's signs: bit a set when the near plane along axis a
    /// is the box's upper one.
    octant: u8,
    tmin: f32,
    tmax: f32,
    eps: f32,
    /// t'' = (t − s)·p.
    s: f64,
    p: f64,
    /// Whether the line may meet the box at or before the `tmin` it was
    /// set up for.
    before: bool,
}

impl Line32 {
    fn new(root: &Aabb, o: DVec3, d: DVec3, tmin: f64, tmax: f64) -> Option<Line32> {
        let m = d.abs().max_element();
        if !(m > 0.0 && m.is_finite() && o.is_finite()) {
            return None;
        }
        // p = 2^e with m / p in [1, 2): o + t·d = o' + t''·(d / p), with
        // o' = o + s·d and t'' = (t − s)·p (s below), every step exact but
        // o'.
        let p = pow2_floor(m);
        let dp = d / p;
        let mdp = dp.abs().max_element();
        // The axes along which the line moves too little for its slab
        // distances to bound it: decided once, for the slabs and the walk.
        let parallel: [bool; 3] = std::array::from_fn(|a| dp[a].abs() < PARALLEL * mdp);
        let both = slabs(root, o, d, parallel);
        let (lo, hi) = clip(both, tmin, tmax)?;
        // The same test over (−∞, tmin], from the same slabs.
        let before = clip(both, f64::NEG_INFINITY, tmin).is_some();
        let s = 0.5 * lo + 0.5 * hi;
        let local = |t: f64| (t - s) * p;
        let tl = local(lo);
        let th = local(hi);
        let tmin32 = below32(tl - tl.abs() * f64::EPSILON);
        let tmax32 = above32(th + th.abs() * f64::EPSILON);
        let tt = (tmin32 as f64).abs().max((tmax32 as f64).abs());
        let eps = above32(10.0 * U32 * tt);
        let op = o + s * d;
        let mut l = Line32 {
            on: [0.0; 3],
            of: [0.0; 3],
            inv: [0.0; 3],
            octant: 0,
            tmin: tmin32,
            tmax: tmax32,
            eps,
            s,
            p,
            before,
        };
        for a in 0..3 {
            let mut err = (o[a].abs() + (s * d[a]).abs()) * (2.0 * f64::EPSILON);
            let parallel = parallel[a];
            if parallel {
                err += dp[a].abs() * tt * 1.01;
            }
            // Not parallel: |d / p| is at least 2⁻⁶⁰, its inverse finite
            // even where 1 / d is not.
            l.inv[a] = if parallel {
                f32::INFINITY
            } else {
                (1.0 / dp[a]) as f32
            };
            let neg = !parallel && dp[a] < 0.0;
            l.octant |= u8::from(neg) << a;
            let up = above32(op[a] + err);
            let dn = below32(op[a] - err);
            (l.on[a], l.of[a]) = if neg { (dn, up) } else { (up, dn) };
        }
        Some(l)
    }

    /// `t` in the line's own `f32` measure, rounded up.
    fn local_up(&self, t: f64) -> f32 {
        let x = (t - self.s) * self.p;
        above32(x + x.abs() * f64::EPSILON)
    }

    /// Which of a node's four boxes the line may meet before `tmax` (a bit
    /// a lane), and where it enters each.
    #[inline(always)]
    fn test<const OCTANT: u8>(&self, n: &MeshNode, tmax: f32) -> (u32, [f32; WIDTH]) {
        #[cfg(target_arch = "x86_64")]
        return self.test_sse::<OCTANT>(n, tmax);
        #[cfg(not(target_arch = "x86_64"))]
        return self.test_portable::<OCTANT>(n, tmax);
    }

    /// [`test`](Self::test), in AVX registers if `AVX`.
    #[inline(always)]
    fn test_with<const OCTANT: u8, const AVX: bool>(
        &self,
        n: &MeshNode,
        tmax: f32,
    ) -> (u32, [f32; WIDTH]) {
        #[cfg(target_arch = "x86_64")]
        if AVX {
            // SAFETY: `AVX` is only set in a walk compiled for AVX, which
            // runs only where the processor has it.
            return unsafe { self.test_avx::<OCTANT>(n, tmax) };
        }
        self.test::<OCTANT>(n, tmax)
    }

    /// [`test`](Self::test) with the eight lanes at once in AVX registers:
    /// the same operations, lane by lane, as the other tests, and the same
    /// answers (a unit test compares them).
    ///
    /// # Safety
    /// The processor must have AVX (and the caller be compiled for it, or
    /// every intrinsic is a call).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn test_avx<const OCTANT: u8>(&self, n: &MeshNode, tmax: f32) -> (u32, [f32; WIDTH]) {
        use std::arch::x86_64::*;
        let mut tn = _mm256_set1_ps(self.tmin);
        let mut tf = _mm256_set1_ps(tmax);
        for a in 0..3 {
            let (np, fp) = n.planes::<OCTANT>(a);
            let inv = _mm256_set1_ps(self.inv[a]);
            let t0 = _mm256_mul_ps(
                _mm256_sub_ps(_mm256_loadu_ps(np.as_ptr()), _mm256_set1_ps(self.on[a])),
                inv,
            );
            let t1 = _mm256_mul_ps(
                _mm256_sub_ps(_mm256_loadu_ps(fp.as_ptr()), _mm256_set1_ps(self.of[a])),
                inv,
            );
            // vmaxps and vminps return their second operand when either is
            // NaN, as maxps and minps: the running bound.
            tn = _mm256_max_ps(t0, tn);
            tf = _mm256_min_ps(t1, tf);
        }
        // cmpleps's own predicate (ordered, signalling).
        let met = _mm256_cmp_ps::<_CMP_LE_OS>(tn, _mm256_add_ps(tf, _mm256_set1_ps(self.eps)));
        let mut out = [0f32; WIDTH];
        _mm256_storeu_ps(out.as_mut_ptr(), tn);
        (_mm256_movemask_ps(met) as u32, out)
    }

    /// [`test`](Self::test) lane by lane, in any processor's own `f32`.
    #[cfg_attr(target_arch = "x86_64", allow(dead_code))]
    #[inline(always)]
    fn test_portable<const OCTANT: u8>(&self, n: &MeshNode, tmax: f32) -> (u32, [f32; WIDTH]) {
        let mut tn = [self.tmin; WIDTH];
        let mut tf = [tmax; WIDTH];
        for a in 0..3 {
            let (np, fp) = n.planes::<OCTANT>(a);
            let (on, of, inv) = (self.on[a], self.of[a], self.inv[a]);
            for k in 0..WIDTH {
                let t0 = (np[k] - on) * inv;
                let t1 = (fp[k] - of) * inv;
                tn[k] = if t0 > tn[k] { t0 } else { tn[k] };
                tf[k] = if t1 < tf[k] { t1 } else { tf[k] };
            }
        }
        let mut hit = 0u32;
        for k in 0..WIDTH {
            hit |= u32::from(tn[k] <= tf[k] + self.eps) << k;
        }
        (hit, tn)
    }

    /// [`test`](Self::test) four lanes at a time in SSE registers: the
    /// same operations, lane by lane, as the portable test, and the
    /// same answers (a unit test compares them).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    #[allow(unused_unsafe)]
    fn test_sse<const OCTANT: u8>(&self, n: &MeshNode, tmax: f32) -> (u32, [f32; WIDTH]) {
        use std::arch::x86_64::*;
        // SAFETY: SSE and SSE2 are part of every x86_64 processor; each
        // load and store reads or writes four `f32` at 0 or 4 of eight.
        unsafe {
            let mut out = [0f32; WIDTH];
            let mut mask = 0u32;
            for h in 0..WIDTH / 4 {
                let mut tn = _mm_set1_ps(self.tmin);
                let mut tf = _mm_set1_ps(tmax);
                for a in 0..3 {
                    let (np, fp) = n.planes::<OCTANT>(a);
                    let inv = _mm_set1_ps(self.inv[a]);
                    let t0 = _mm_mul_ps(
                        _mm_sub_ps(
                            _mm_loadu_ps(np.as_ptr().add(4 * h)),
                            _mm_set1_ps(self.on[a]),
                        ),
                        inv,
                    );
                    let t1 = _mm_mul_ps(
                        _mm_sub_ps(
                            _mm_loadu_ps(fp.as_ptr().add(4 * h)),
                            _mm_set1_ps(self.of[a]),
                        ),
                        inv,
                    );
                    // maxps and minps return their second operand when
                    // either is NaN: the running bound.
                    tn = _mm_max_ps(t0, tn);
                    tf = _mm_min_ps(t1, tf);
                }
                let met = _mm_cmple_ps(tn, _mm_add_ps(tf, _mm_set1_ps(self.eps)));
                _mm_storeu_ps(out.as_mut_ptr().add(4 * h), tn);
                mask |= (_mm_movemask_ps(met) as u32) << (4 * h);
            }
            (mask, out)
        }
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    /// Both of a line's tests of `n`, for the octant of its direction.
    fn both(l: &Line32, n: &MeshNode, tmax: f32) -> [(u32, [f32; WIDTH]); 2] {
        by_octant!(l.octant, O => [l.test_sse::<O>(n, tmax), l.test_portable::<O>(n, tmax)])
    }

    /// The AVX test, compiled for AVX.
    #[target_feature(enable = "avx")]
    unsafe fn avx_test<const O: u8>(l: &Line32, n: &MeshNode, tmax: f32) -> (u32, [f32; WIDTH]) {
        l.test_avx::<O>(n, tmax)
    }

    #[test]
    fn pow2_floor_is_the_power_of_two_below_every_float() {
        // 2^e from its bits: the exponent field for a normal one, the one
        // set bit of the fraction for a subnormal one.
        let two_to = |e: i32| {
            if e >= -1022 {
                f64::from_bits(((e + 1023) as u64) << 52)
            } else {
                f64::from_bits(1u64 << (e + 1074))
            }
        };
        for e in -1074..=1023 {
            let p = two_to(e);
            assert_eq!(pow2_floor(p), p, "2^{e}");
            // The greatest float below 2^(e+1), and a point in between.
            if e < 1023 {
                let next = two_to(e + 1);
                let below = f64::from_bits(next.to_bits() - 1);
                assert_eq!(pow2_floor(below), p, "below 2^{}", e + 1);
            }
            // (1.5 · 2^-1074 is not a float: it rounds to 2^-1073.)
            if e > -1074 {
                assert_eq!(pow2_floor(p * 1.5), p, "1.5 * 2^{e}");
            }
        }
    }

    #[test]
    fn the_sse_node_test_answers_as_the_portable_one() {
        let mut x: u64 = 11;
        let mut next = move || {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let root = Aabb {
            min: DVec3::splat(-4.0),
            max: DVec3::splat(4.0),
        };
        let (mut met, mut checked, mut avx_checked, mut grazed) = (0, 0, 0, 0);
        for k in 0..20_000 {
            let mut n = EMPTY_NODE;
            // Up to eight boxes, some flat, the rest of the lanes empty.
            for lane in 0..(k % WIDTH + 1) {
                for a in 0..3 {
                    let lo = (next() * 8.0 - 4.0) as f32;
                    let size = if next() < 0.1 {
                        0.0
                    } else {
                        next() as f32 * 6.0
                    };
                    n.b[a][lane] = lo;
                    n.b[a + 3][lane] = lo + size;
                }
                n.child[lane] = lane as u32;
            }
            // Lines aimed at the boxes' middle, some along an axis or in
            // a plane.
            let o = DVec3::new(next(), next(), next()) * 12.0 - DVec3::splat(6.0);
            let mut d = DVec3::new(next(), next(), next()) * 3.0 - DVec3::splat(1.5) - o;
            if k % 5 == 0 {
                d[k % 3] = 0.0;
            }
            let mut o = o;
            if k % 7 == 0 {
                // Along an axis, in a plane of the first box (0·∞ is NaN
                // there: such a slab constrains nothing).
                let axis = k % 3;
                d = [DVec3::X, DVec3::NEG_Y, DVec3::Z][axis];
                for a in (0..3).filter(|&a| a != axis) {
                    o[a] = 0.0;
                    // The line's origin there is rounded out by one step
                    // either way (`above32`, `below32`).
                    let side = (k / 7) % 2;
                    let step = f32::from_bits(1);
                    n.b[a + 3 * side][0] = if side == 0 { step } else { -step };
                    n.b[a][0] = n.b[a][0].min(n.b[a + 3][0]);
                    n.b[a + 3][0] = n.b[a][0].max(n.b[a + 3][0]);
                }
            }
            let Some(l) = Line32::new(&root, o, d, f64::NEG_INFINITY, f64::INFINITY) else {
                continue;
            };
            if k % 4 == 3 && k % 7 != 0 {
                // A box with a corner by the line: met only within the
                // test's ε of a graze, or just missed.
                let lane = k % WIDTH;
                let t = l.s + (next() - 0.5) * 0.1;
                // Entered along x up to three ε after it is left along y.
                let late = next() * 3.0 * f64::from(l.eps) / l.p;
                let p = o + t * d;
                let size = 0.5 + next() as f32;
                let (x, y) = ((o.x + (t + late) * d.x) as f32, p.y as f32);
                (n.b[0][lane], n.b[3][lane]) = if d.x > 0.0 {
                    (x, x + size)
                } else {
                    (x - size, x)
                };
                (n.b[1][lane], n.b[4][lane]) = if d.y > 0.0 {
                    (y - size, y)
                } else {
                    (y, y + size)
                };
                n.b[2][lane] = p.z as f32 - size;
                n.b[5][lane] = p.z as f32 + size;
                n.child[lane] = lane as u32;
            }
            let [sse, portable] = both(&l, &n, l.tmax);
            let flush = Line32 { eps: 0.0, ..l };
            grazed += (portable.0 & !both(&flush, &n, l.tmax)[1].0).count_ones();
            assert_eq!(sse.0, portable.0, "{o} {d}");
            for lane in 0..WIDTH {
                assert_eq!(sse.1[lane].to_bits(), portable.1[lane].to_bits(), "{o} {d}");
            }
            if has_avx() {
                // SAFETY: the processor has AVX.
                let avx = by_octant!(l.octant, O => unsafe { avx_test::<O>(&l, &n, l.tmax) });
                assert_eq!(avx.0, portable.0, "{o} {d}");
                for lane in 0..WIDTH {
                    assert_eq!(avx.1[lane].to_bits(), portable.1[lane].to_bits(), "{o} {d}");
                }
                avx_checked += 1;
            }
            met += sse.0.count_ones();
            checked += 1;
        }
        assert!(checked > 15_000 && met > 4_000, "{checked} {met}");
        // Boxes met only thanks to ε, on which the tests must agree too.
        assert!(grazed > 200, "{grazed}");
        assert!(avx_checked == checked || !has_avx());
    }
}
