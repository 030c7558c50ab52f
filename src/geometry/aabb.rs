//! Axis-aligned bounding boxes and the slab test.

use super::Ray;
use crate::math::robust::GAMMA3;
use glam::DVec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };
    pub const EVERYTHING: Aabb = Aabb {
        min: DVec3::splat(f64::NEG_INFINITY),
        max: DVec3::splat(f64::INFINITY),
    };

    pub fn new(min: DVec3, max: DVec3) -> Aabb {
        Aabb { min, max }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Whether the box is finite on every side.
    pub fn is_bounded(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.min(o.min), self.max.max(o.max))
    }

    pub fn intersect(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.max(o.min), self.max.min(o.max))
    }

    pub fn include(&self, p: DVec3) -> Aabb {
        Aabb::new(self.min.min(p), self.max.max(p))
    }

    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// The box's volume (0 for an empty one).
    pub fn volume(&self) -> f64 {
        let e = (self.max - self.min).max(DVec3::ZERO);
        e.x * e.y * e.z
    }

    /// Whether the ray meets the box for some `t` in `[tmin, tmax]`.
    ///
    /// NaN-safe: a zero direction component gives ±∞ slab distances, and a
    /// `0·∞` NaN (origin exactly on a slab plane) is ignored. The far distance is widened by
    /// `1 + 2γ₃` so that rounding never culls a box the ray grazes.
    pub fn hit(&self, ray: &Ray, tmin: f64, tmax: f64) -> bool {
        self.entry(ray, tmin, tmax).is_some()
    }

    /// Where the ray enters the box within `[tmin, tmax]` (`tmin` if it
    /// starts inside), or `None` if it misses; the same test as [`hit`].
    ///
    /// [`hit`]: Aabb::hit
    #[inline]
    pub fn entry(&self, ray: &Ray, tmin: f64, tmax: f64) -> Option<f64> {
        let t0 = (self.min - ray.origin) * ray.inv_dir;
        let t1 = (self.max - ray.origin) * ray.inv_dir;
        // Branch-free min and max (one `minsd`/`maxsd` each) that return
        // their second operand when the first is NaN; the running bounds
        // are always the second operand, so a NaN slab distance constrains
        // nothing.
        let lt = |a: f64, b: f64| if a < b { a } else { b };
        let gt = |a: f64, b: f64| if a > b { a } else { b };
        let mut lo = tmin;
        let mut far = f64::INFINITY;
        for i in 0..3 {
            let (a, b) = (t0[i], t1[i]);
            lo = gt(lt(a, b), lo);
            far = lt(gt(a, b), far);
        }
        // Widened once, after the least far distance is chosen: rounding is
        // monotonic, so this is the least of the widened ones, to the bit.
        let hi = lt(widened(far), tmax);
        (lo <= hi).then_some(lo)
    }
}

/// A far slab distance moved outward by 2γ₃ of itself, before the origin
/// as after it (a mesh counts its crossings from the line's start).
#[inline(always)]
fn widened(t: f64) -> f64 {
    t * if t >= 0.0 { WIDEN } else { 1.0 / WIDEN }
}

/// The factor of [`widened`] (and of its SSE form in [`AabbLanes`]).
const WIDEN: f64 = 1.0 + 2.0 * GAMMA3;

/// `N` boxes laid out axis by axis, so that one slab test serves them all
/// (the four boxes of a wide hierarchy node, four children of a union).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AabbLanes<const N: usize> {
    min: [[f64; N]; 3],
    max: [[f64; N]; 3],
}

impl<const N: usize> AabbLanes<N> {
    /// `boxes` (at most `N`) in the first lanes; a lane left over holds
    /// [`Aabb::EMPTY`], whose answer means nothing (the caller knows how
    /// many lanes it filled).
    pub fn of(boxes: &[Aabb]) -> AabbLanes<N> {
        assert!(boxes.len() <= N, "more boxes than lanes");
        let at = |k: usize| boxes.get(k).unwrap_or(&Aabb::EMPTY);
        AabbLanes {
            min: std::array::from_fn(|i| std::array::from_fn(|k| at(k).min[i])),
            max: std::array::from_fn(|i| std::array::from_fn(|k| at(k).max[i])),
        }
    }

    /// [`Aabb::entry`] of every lane's box, with the same operations in
    /// the same order (so the same bits), written lane by lane so that the
    /// compiler can do the lanes side by side.
    #[inline]
    pub fn entries(&self, ray: &Ray, tmin: f64, tmax: f64) -> [Option<f64>; N] {
        let (met, t) = self.entries_met(ray, tmin, tmax);
        std::array::from_fn(|k| (met >> k & 1 != 0).then_some(t[k]))
    }

    /// [`entries`](Self::entries) as a bit a lane (set where the ray meets
    /// the box) and the entries (meaningless where the bit is clear): what
    /// a caller that gathers the lanes met reads with no `Option` a lane.
    #[inline]
    pub fn entries_met(&self, ray: &Ray, tmin: f64, tmax: f64) -> (u32, [f64; N]) {
        #[cfg(target_arch = "x86_64")]
        if N % 2 == 0 {
            return self.entries_sse(ray, tmin, tmax);
        }
        let e = self.entries_portable(ray, tmin, tmax);
        let met = (0..N).fold(0, |m, k| m | (e[k].is_some() as u32) << k);
        (met, e.map(|e| e.unwrap_or(0.0)))
    }

    /// [`entries_met`](Self::entries_met) two lanes a register: `minpd(a,
    /// b)` is `if a < b { a } else { b }` and `maxpd(a, b)` `if a > b { a }
    /// else { b }`, the portable test's selects exactly, NaN included (a
    /// unit test compares the two).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn entries_sse(&self, ray: &Ray, tmin: f64, tmax: f64) -> (u32, [f64; N]) {
        use std::arch::x86_64::*;
        let mut out = [0.0; N];
        let mut met = 0;
        // SAFETY: SSE2 is part of x86_64; every load and store stays within
        // the arrays (N even, lanes k and k + 1).
        unsafe {
            let zero = _mm_setzero_pd();
            let up = _mm_set1_pd(WIDEN);
            let down = _mm_set1_pd(1.0 / WIDEN);
            let mut k = 0;
            while k + 1 < N {
                let mut lo = _mm_set1_pd(tmin);
                let mut far = _mm_set1_pd(f64::INFINITY);
                for i in 0..3 {
                    let o = _mm_set1_pd(ray.origin[i]);
                    let inv = _mm_set1_pd(ray.inv_dir[i]);
                    let a = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&self.min[i][k]), o), inv);
                    let b = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&self.max[i][k]), o), inv);
                    lo = _mm_max_pd(_mm_min_pd(a, b), lo);
                    far = _mm_min_pd(_mm_max_pd(a, b), far);
                }
                // widened(far): × WIDEN where far ≥ 0, × 1/WIDEN elsewhere.
                let ge = _mm_cmpge_pd(far, zero);
                let m = _mm_or_pd(_mm_and_pd(ge, up), _mm_andnot_pd(ge, down));
                let hi = _mm_min_pd(_mm_mul_pd(far, m), _mm_set1_pd(tmax));
                let ok = _mm_movemask_pd(_mm_cmple_pd(lo, hi)) as u32;
                _mm_storeu_pd(out.as_mut_ptr().add(k), lo);
                met |= ok << k;
                k += 2;
            }
        }
        (met, out)
    }

    /// [`entries_met`](Self::entries_met) four lanes a register (AVX):
    /// `vminpd`, `vmaxpd` and the ordered comparisons are the SSE2 test's
    /// operations lane for lane, so the same bits (a unit test compares
    /// them).
    ///
    /// # Safety
    /// The processor must have AVX; only worth calling where inlined into
    /// a function compiled for it (such as `AabbLanes::gather_avx`),
    /// else every intrinsic is a call.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub unsafe fn entries_met_avx(&self, ray: &Ray, tmin: f64, tmax: f64) -> (u32, [f64; N]) {
        use std::arch::x86_64::*;
        assert!(N % 4 == 0, "four lanes a register");
        let mut out = [0.0; N];
        let mut met = 0;
        // SAFETY: the caller's processor has AVX; every load and store
        // stays within the arrays (N a multiple of four, lanes k to k + 3).
        unsafe {
            let zero = _mm256_setzero_pd();
            let up = _mm256_set1_pd(WIDEN);
            let down = _mm256_set1_pd(1.0 / WIDEN);
            let mut k = 0;
            while k + 3 < N {
                let mut lo = _mm256_set1_pd(tmin);
                let mut far = _mm256_set1_pd(f64::INFINITY);
                for i in 0..3 {
                    let o = _mm256_set1_pd(ray.origin[i]);
                    let inv = _mm256_set1_pd(ray.inv_dir[i]);
                    let a = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(&self.min[i][k]), o), inv);
                    let b = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(&self.max[i][k]), o), inv);
                    lo = _mm256_max_pd(_mm256_min_pd(a, b), lo);
                    far = _mm256_min_pd(_mm256_max_pd(a, b), far);
                }
                let ge = _mm256_cmp_pd::<_CMP_GE_OQ>(far, zero);
                let m = _mm256_or_pd(_mm256_and_pd(ge, up), _mm256_andnot_pd(ge, down));
                let hi = _mm256_min_pd(_mm256_mul_pd(far, m), _mm256_set1_pd(tmax));
                let ok = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(lo, hi)) as u32;
                _mm256_storeu_pd(out.as_mut_ptr().add(k), lo);
                met |= ok << k;
                k += 4;
            }
        }
        (met, out)
    }

    /// [`entries`](Self::entries) in plain Rust.
    #[inline(always)]
    fn entries_portable(&self, ray: &Ray, tmin: f64, tmax: f64) -> [Option<f64>; N] {
        let lt = |a: f64, b: f64| if a < b { a } else { b };
        let gt = |a: f64, b: f64| if a > b { a } else { b };
        let mut lo = [tmin; N];
        let mut far = [f64::INFINITY; N];
        for i in 0..3 {
            let (o, inv) = (ray.origin[i], ray.inv_dir[i]);
            for k in 0..N {
                let a = (self.min[i][k] - o) * inv;
                let b = (self.max[i][k] - o) * inv;
                lo[k] = gt(lt(a, b), lo[k]);
                far[k] = lt(gt(a, b), far[k]);
            }
        }
        std::array::from_fn(|k| (lo[k] <= lt(widened(far[k]), tmax)).then_some(lo[k]))
    }
}

impl AabbLanes<4> {
    /// For each box of `lanes` (four a group; `ids[j]` names box j, and
    /// boxes past the end of `ids` are empty lanes) that the ray meets
    /// within [tmin, tmax], `met(entry, id)`, in the boxes' order: four
    /// boxes a register where the processor has AVX, two where it has only
    /// SSE2 — the same bits either way.
    #[inline]
    pub fn gather(
        lanes: &[AabbLanes<4>],
        ids: &[u32],
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        met: impl FnMut(f64, u32),
    ) {
        #[cfg(target_arch = "x86_64")]
        if has_avx() {
            // SAFETY: the processor has AVX.
            return unsafe { Self::gather_avx(lanes, ids, ray, tmin, tmax, met) };
        }
        Self::gather_with::<false>(lanes, ids, ray, tmin, tmax, met)
    }

    /// [`entries_met`](Self::entries_met) by [`entries_met_avx`] where the
    /// processor has AVX (a call, for a caller not itself compiled for it:
    /// a wide hierarchy's node), else by SSE2: the same bits.
    ///
    /// [`entries_met_avx`]: Self::entries_met_avx
    #[inline]
    pub fn entries_met_any(&self, ray: &Ray, tmin: f64, tmax: f64) -> (u32, [f64; 4]) {
        #[cfg(target_arch = "x86_64")]
        if has_avx() {
            // SAFETY: the processor has AVX.
            return unsafe { self.entries_met_avx_call(ray, tmin, tmax) };
        }
        self.entries_met(ray, tmin, tmax)
    }

    /// [`entries_met_avx`](Self::entries_met_avx) compiled for AVX.
    ///
    /// # Safety
    /// The processor must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn entries_met_avx_call(&self, ray: &Ray, tmin: f64, tmax: f64) -> (u32, [f64; 4]) {
        self.entries_met_avx(ray, tmin, tmax)
    }

    /// [`gather`](Self::gather) compiled for AVX.
    ///
    /// # Safety
    /// The processor must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn gather_avx(
        lanes: &[AabbLanes<4>],
        ids: &[u32],
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        met: impl FnMut(f64, u32),
    ) {
        Self::gather_with::<true>(lanes, ids, ray, tmin, tmax, met)
    }

    /// [`gather`](Self::gather), its lanes by [`entries_met_avx`] if
    /// `AVX` (only where inlined into [`gather_avx`]), else by
    /// [`entries_met`].
    ///
    /// [`entries_met_avx`]: Self::entries_met_avx
    /// [`gather_avx`]: Self::gather_avx
    /// [`entries_met`]: Self::entries_met
    #[inline(always)]
    fn gather_with<const AVX: bool>(
        lanes: &[AabbLanes<4>],
        ids: &[u32],
        ray: &Ray,
        tmin: f64,
        tmax: f64,
        mut met: impl FnMut(f64, u32),
    ) {
        for (l, group) in lanes.iter().zip(ids.chunks(4)) {
            #[cfg(target_arch = "x86_64")]
            let (bits, t) = if AVX {
                // SAFETY: `AVX` only inside `gather_avx`, called where the
                // processor has AVX.
                unsafe { l.entries_met_avx(ray, tmin, tmax) }
            } else {
                l.entries_met(ray, tmin, tmax)
            };
            #[cfg(not(target_arch = "x86_64"))]
            let (bits, t) = l.entries_met(ray, tmin, tmax);
            // The lanes filled, in order.
            let mut m = bits & ((1 << group.len()) - 1);
            while m != 0 {
                let k = m.trailing_zeros() as usize;
                met(t[k], group[k]);
                m &= m - 1;
            }
        }
    }
}

/// Whether this processor has AVX (asked once: the answer is kept).
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn has_avx() -> bool {
    std::arch::is_x86_feature_detected!("avx")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AVX lanes' test, compiled for AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn avx_entries(l: &AabbLanes<4>, ray: &Ray, tmin: f64, tmax: f64) -> (u32, [f64; 4]) {
        l.entries_met_avx(ray, tmin, tmax)
    }

    fn unit_box() -> Aabb {
        Aabb::new(DVec3::splat(-1.0), DVec3::splat(1.0))
    }

    #[test]
    fn zero_direction_components_are_handled_without_nan() {
        let b = unit_box();
        // Parallel to x, inside the y and z slabs: hits.
        assert!(b.hit(
            &Ray::new(DVec3::new(-5.0, 0.5, 0.5), DVec3::X),
            0.0,
            f64::INFINITY
        ));
        // Parallel to x, outside the y slab: misses.
        assert!(!b.hit(
            &Ray::new(DVec3::new(-5.0, 1.5, 0.5), DVec3::X),
            0.0,
            f64::INFINITY
        ));
        // Origin exactly on a slab plane with a zero component: 0·∞ is NaN,
        // which must neither hit everything nor poison the answer. This ray
        // runs in the face y = 1: it touches the box, and a bound must be
        // conservative, so it hits; the same line off the box (z = 5) misses.
        let on_plane = Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::X);
        assert!(b.hit(&on_plane, 0.0, f64::INFINITY));
        assert_eq!(b.entry(&on_plane, 0.0, f64::INFINITY), Some(4.0));
        assert!(!b.hit(
            &Ray::new(DVec3::new(-5.0, 1.0, 5.0), DVec3::X),
            0.0,
            f64::INFINITY
        ));
    }

    #[test]
    fn the_range_limits_the_test() {
        let b = unit_box();
        let r = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X);
        assert!(b.hit(&r, 0.0, 4.5));
        assert!(!b.hit(&r, 0.0, 3.9));
        assert!(!b.hit(&r, 6.1, 10.0));
    }

    use proptest::prelude::*;

    /// Small integers make coincidences likely: origins on slab planes,
    /// zero direction components, flat boxes.
    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-4i32..=4).prop_map(f64::from), -4.0..4.0f64]
    }

    fn vec3() -> impl Strategy<Value = DVec3> {
        (coord(), coord(), coord()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn aabb() -> impl Strategy<Value = Aabb> {
        (vec3(), vec3()).prop_map(|(a, b)| Aabb::new(a.min(b), a.max(b)))
    }

    /// The slab test as first written: each axis's far distance widened
    /// before the least is taken.
    fn entry_widening_each_axis(b: &Aabb, ray: &Ray, tmin: f64, tmax: f64) -> Option<f64> {
        let t0 = (b.min - ray.origin) * ray.inv_dir;
        let t1 = (b.max - ray.origin) * ray.inv_dir;
        let lt = |a: f64, b: f64| if a < b { a } else { b };
        let gt = |a: f64, b: f64| if a > b { a } else { b };
        let (mut lo, mut hi) = (tmin, tmax);
        for i in 0..3 {
            let (a, b) = (t0[i], t1[i]);
            lo = gt(lt(a, b), lo);
            hi = lt(widened(gt(a, b)), hi);
        }
        (lo <= hi).then_some(lo)
    }

    /// Far distances that round together when widened, on both sides of
    /// zero, and the infinities of zero direction components.
    fn far_coord() -> impl Strategy<Value = f64> {
        prop_oneof![
            coord(),
            (-4i32..=4).prop_map(|k| f64::from(k) * (1.0 + f64::EPSILON)),
            Just(0.0),
            Just(-0.0),
            -1e-300..1e-300f64,
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]
        #[test]
        fn widening_the_least_far_distance_is_widening_each(
            lo in (far_coord(), far_coord(), far_coord()),
            hi in (far_coord(), far_coord(), far_coord()),
            o in (far_coord(), far_coord(), far_coord()),
            d in (far_coord(), far_coord(), far_coord()),
            tmin in prop_oneof![Just(0.0), Just(f64::NEG_INFINITY), -2.0..2.0f64],
            tmax in prop_oneof![Just(f64::INFINITY), -2.0..8.0f64],
            at_corner in any::<bool>(),
        ) {
            let (a, b) = (DVec3::from(lo), DVec3::from(hi));
            let bx = Aabb::new(a.min(b), a.max(b));
            // Aimed at a corner, the slab distances meet there but for
            // rounding: the widening decides.
            let d = if at_corner { bx.min - DVec3::from(o) } else { DVec3::from(d) };
            let ray = Ray::new(DVec3::from(o), d);
            let got = bx.entry(&ray, tmin, tmax);
            let want = entry_widening_each_axis(&bx, &ray, tmin, tmax);
            prop_assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits));
        }

        #[test]
        fn a_pair_gives_the_same_bits_as_two_single_tests(
            a in aabb(), b in aabb(), o in vec3(), d in vec3(),
            tmin in prop_oneof![Just(0.0), 0.0..2.0f64],
            tmax in prop_oneof![Just(f64::INFINITY), 2.0..8.0f64],
        ) {
            let ray = Ray::new(o, d);
            let got = AabbLanes::<2>::of(&[a, b]).entries(&ray, tmin, tmax);
            let want = [a.entry(&ray, tmin, tmax), b.entry(&ray, tmin, tmax)];
            prop_assert_eq!(got.map(|e| e.map(f64::to_bits)), want.map(|e| e.map(f64::to_bits)));
        }

        #[test]
        fn the_portable_lanes_give_the_same_bits_as_the_sse_ones(
            boxes in proptest::collection::vec(aabb(), 4), o in vec3(), d in vec3(),
            tmin in prop_oneof![Just(0.0), Just(f64::NEG_INFINITY), -2.0..2.0f64],
            tmax in prop_oneof![Just(f64::INFINITY), -2.0..8.0f64],
        ) {
            let ray = Ray::new(o, d);
            let l = AabbLanes::<4>::of(&boxes);
            let bits = |e: [Option<f64>; 4]| e.map(|e| e.map(f64::to_bits));
            // (`entries` reads `entries_met`'s bits and values: both checked.)
            prop_assert_eq!(bits(l.entries(&ray, tmin, tmax)), bits(l.entries_portable(&ray, tmin, tmax)));
        }

        /// Where the processor has AVX (the machines this project runs on
        /// do): its four lanes a register give the SSE2 lanes' bits and met
        /// lanes, special entries (origins on slab planes, zero direction
        /// components, infinite and negative ranges) included, called
        /// inlined or through `entries_met_any`; `gather` gives the same
        /// children and entries as the per-box tests.
        #[cfg(target_arch = "x86_64")]
        #[test]
        fn avx_lanes_give_the_same_bits_as_sse_ones(
            boxes in proptest::collection::vec(aabb(), 1..=8), o in vec3(), d in vec3(),
            tmin in prop_oneof![Just(0.0), Just(f64::NEG_INFINITY), -2.0..2.0f64],
            tmax in prop_oneof![Just(f64::INFINITY), -2.0..8.0f64],
        ) {
            if !has_avx() {
                return Ok(());
            }
            let ray = Ray::new(o, d);
            let lanes: Vec<AabbLanes<4>> = boxes.chunks(4).map(AabbLanes::of).collect();
            for l in &lanes {
                // SAFETY: the processor has AVX (assumed above).
                let (am, at) = unsafe { avx_entries(l, &ray, tmin, tmax) };
                let (sm, st) = l.entries_met(&ray, tmin, tmax);
                let (ym, yt) = l.entries_met_any(&ray, tmin, tmax);
                prop_assert_eq!(am, sm);
                prop_assert_eq!(ym, sm);
                for k in 0..4 {
                    if sm >> k & 1 != 0 {
                        prop_assert_eq!(at[k].to_bits(), st[k].to_bits());
                        prop_assert_eq!(yt[k].to_bits(), st[k].to_bits());
                    }
                }
            }
            let ids: Vec<u32> = (0..boxes.len() as u32).map(|k| 7 * k + 3).collect();
            let mut got = Vec::new();
            AabbLanes::gather(&lanes, &ids, &ray, tmin, tmax, |t, c| got.push((t.to_bits(), c)));
            let want: Vec<(u64, u32)> = boxes
                .iter()
                .zip(&ids)
                .filter_map(|(b, &c)| b.entry(&ray, tmin, tmax).map(|t| (t.to_bits(), c)))
                .collect();
            prop_assert_eq!(got, want);
        }

        #[test]
        fn four_lanes_give_the_same_bits_as_single_tests(
            boxes in proptest::collection::vec(aabb(), 1..=4), o in vec3(), d in vec3(),
            tmin in prop_oneof![Just(0.0), 0.0..2.0f64],
            tmax in prop_oneof![Just(f64::INFINITY), 2.0..8.0f64],
        ) {
            let ray = Ray::new(o, d);
            let got = AabbLanes::<4>::of(&boxes).entries(&ray, tmin, tmax);
            for (k, b) in boxes.iter().enumerate() {
                let want = b.entry(&ray, tmin, tmax);
                prop_assert_eq!(got[k].map(f64::to_bits), want.map(f64::to_bits));
            }
        }
    }
}
