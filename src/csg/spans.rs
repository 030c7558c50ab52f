//! Span lists along a ray and their union, intersection, difference and
//! symmetric difference.
//!
//! A list holds the disjoint intervals of `t` inside a solid, sorted, each
//! end remembering which primitive's surface made it ([`Boundary`]).
//!
//! # The rule for equal endpoints
//! Combination sweeps both lists in `t`. At each distinct `t` it applies
//! every change of both operands at once, and writes a boundary only if the
//! result's membership changes there. Two operands' boundaries closer than
//! [`coincidence`] (a few hundred ulps of the ray's scale: see
//! `math::robust`) count as the same `t`, so faces shared by two
//! primitives resolve the same way in every pixel even though each was
//! reached through its own transform. So touching spans merge (`[0,1] ∪
//! [1,2] = [0,2]`), spans that only touch intersect to nothing, and `A − A`
//! is empty: a result never holds a span of zero length. When both operands
//! change at the same `t`, the boundary is credited to the operand whose
//! change alone would move the result the same way, A before B, and to A
//! when neither alone would. Surfaces credited to the subtracted operand of
//! a difference have their normals flipped.

use crate::geometry::{Part, NO_PART};
use crate::math::boolean::Op;
use crate::math::robust::coincidence;

/// One end of a span: where a ray crosses a primitive's surface.
///
/// Sixteen bytes: the part (a cube face, a mesh's triangle, a polygon's
/// edge: up to 2³¹ − 1 of them) and the flip share one word.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boundary {
    pub t: f64,
    /// Index of the primitive whose surface this is.
    pub prim: u32,
    /// The part in the low 31 bits, the flip in the top one.
    bits: u32,
}

const FLIP: u32 = 1 << 31;

impl Boundary {
    /// A crossing of primitive `prim`'s surface at `t`, on `part`.
    #[inline]
    pub const fn new(t: f64, prim: u32, part: Part) -> Boundary {
        Boundary {
            t,
            prim,
            bits: part & !FLIP,
        }
    }

    /// An open end at ±∞, or the unknown edge of a clipped span.
    pub const fn open(t: f64) -> Boundary {
        Boundary::new(t, u32::MAX, NO_PART)
    }

    /// Which part of the primitive's surface this is.
    #[inline]
    pub const fn part(&self) -> Part {
        self.bits & !FLIP
    }

    /// Whether the primitive's outward normal points *into* the solid
    /// here: set for surfaces taken from the subtracted children of a
    /// difference.
    #[inline]
    pub const fn flip(&self) -> bool {
        self.bits & FLIP != 0
    }

    /// The same crossing with its normal turned the other way.
    #[inline]
    pub const fn flipped(self) -> Boundary {
        Boundary {
            bits: self.bits ^ FLIP,
            ..self
        }
    }

    /// Whether this is a real surface crossing.
    pub fn is_surface(&self) -> bool {
        self.prim != u32::MAX && self.t.is_finite()
    }
}

/// An interval of the ray inside a solid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    pub enter: Boundary,
    pub exit: Boundary,
}

/// Whether `t` lies inside one of the spans (ends included).
pub fn contains(list: &[Span], t: f64) -> bool {
    list.iter().any(|s| s.enter.t <= t && t <= s.exit.t)
}

/// The next boundary a sweep meets in a list: the enter of span `i` when
/// outside, its exit when inside.
#[inline]
fn next(list: &[Span], i: usize, inside: bool) -> Option<Boundary> {
    list.get(i).map(|s| if inside { s.exit } else { s.enter })
}

/// `a op b`, sweeping both sorted lists once; `scale` is the largest
/// absolute coordinate of the ray's origin (0 for abstract lists).
pub fn combine(op: Op, a: &[Span], b: &[Span], scale: f64) -> Vec<Span> {
    let mut out = Vec::new();
    combine_into(op, a, b, scale, &mut out);
    out
}

/// What `a op b` is, without a sweep, when a side is empty or a union's
/// lists lie apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quick {
    /// `a` itself.
    A,
    /// `b` itself (`a` is empty).
    B,
    Empty,
    /// `a` then `b`: a union whose `b` begins after `a` ends, farther than
    /// the coincidence bound.
    AThenB,
    /// `b` then `a`: a union whose `b` ends before `a` begins (a part in
    /// front of a floor).
    BThenA,
}

/// The answer to `a op b` that needs no sweep, or `None`; `scale` as for
/// [`combine`].
#[inline]
pub fn quick(op: Op, a: &[Span], b: &[Span], scale: f64) -> Option<Quick> {
    quick_empty(op, a, b).or_else(|| {
        if op.b_alone() {
            apart(a, b, scale)
        } else {
            None
        }
    })
}

/// The answer when a side is empty.
#[inline]
pub fn quick_empty(op: Op, a: &[Span], b: &[Span]) -> Option<Quick> {
    match op {
        Op::Union | Op::Xor if a.is_empty() => Some(Quick::B),
        Op::Union | Op::Difference | Op::Xor if b.is_empty() => Some(Quick::A),
        Op::Intersection | Op::Difference if a.is_empty() => Some(Quick::Empty),
        Op::Intersection if b.is_empty() => Some(Quick::Empty),
        _ => None,
    }
}

/// The union (or symmetric difference) of two non-empty lists apart by
/// more than the coincidence bound: the two lists one after the other, the
/// common case of a wide union.
#[inline]
pub fn apart(a: &[Span], b: &[Span], scale: f64) -> Option<Quick> {
    if ends_before(&a[a.len() - 1], &b[0], scale) {
        Some(Quick::AThenB)
    } else if ends_before(&b[b.len() - 1], &a[0], scale) {
        Some(Quick::BThenA)
    } else {
        None
    }
}

/// Whether span `x` ends before `y` starts, beyond the coincidence bound
/// (a sweep meets their ends in different steps).
#[inline]
pub fn ends_before(x: &Span, y: &Span, scale: f64) -> bool {
    y.enter.t > x.exit.t + coincidence(x.exit.t, scale)
}

/// The union of two single spans that are not [`apart`]: what
/// [`sweep_into`] gives, one span, with its events written out (the case
/// of two overlapping solids, the commonest merge of a first-hit query,
/// at a tenth of the sweep's work). `None` for ends out of order or NaN,
/// which the sweep itself must see.
///
/// The sweep's steps, A = [a0, a1], B = [b0, b1], each step taking every
/// end within the coincidence bound of the least one left: it enters at
/// the least start, credited to A if A starts within the bound of it; if
/// only one started, the other's start is within the bound of the first
/// one's end (they are not apart), so the next step takes it, with that
/// end too if the end is within the bound — then the later one's end is
/// the exit; otherwise both are inside and the exit is the step that
/// ends them: A's, at the lesser end, if both ends are within the bound
/// of it, else the later one's own.
#[inline]
pub fn union_one(a: &Span, b: &Span, scale: f64) -> Option<Span> {
    let (a0, a1, b0, b1) = (a.enter.t, a.exit.t, b.enter.t, b.exit.t);
    if !(a0 <= a1 && b0 <= b1) {
        return None;
    }
    let near = |t: f64| t + coincidence(t, scale);
    let at = |mut x: Boundary, t: f64| {
        x.t = t;
        x
    };
    let t = a0.min(b0);
    let n = near(t);
    let (sa, sb) = (a0 <= n, b0 <= n);
    let enter = if sa { at(a.enter, t) } else { b.enter };
    // Both inside: the step that ends them.
    let both = || {
        let t = a1.min(b1);
        let n = near(t);
        match (a1 <= n, b1 <= n) {
            (true, true) => at(a.exit, t),
            (true, false) => b.exit,
            _ => a.exit,
        }
    };
    let exit = if sa && sb {
        both()
    } else if sa {
        // B starts at the next step; A may end there too.
        if a1 <= near(a1.min(b0)) {
            b.exit
        } else {
            both()
        }
    } else if b1 <= near(a0.min(b1)) {
        // B ends where A starts.
        a.exit
    } else {
        both()
    };
    Some(Span { enter, exit })
}

/// The intersection or difference of two single spans whose ends are
/// farther apart, across the two, than the coincidence bound: what
/// [`sweep_into`] gives, up to two spans and how many. Each of the
/// sweep's steps then takes one end, credited to its own span, so the
/// answer is the ends' order (the lens of two spheres, a hole through a
/// slab). `None` when two ends of the two spans lie within the bound (the
/// sweep's rule for equal ends decides there), or for ends out of order,
/// equal or NaN, or for the other operations.
#[inline]
pub fn cut_one(op: Op, a: &Span, b: &Span, scale: f64) -> Option<([Span; 2], usize)> {
    let (a0, a1, b0, b1) = (a.enter.t, a.exit.t, b.enter.t, b.exit.t);
    if !(a0 < a1 && b0 < b1) {
        return None;
    }
    // A bound at least each finite end's own; the sweep steps an end y
    // with t when y ≤ t + bound(t), so y > t + this, rounded as it is,
    // keeps them apart (an infinite end's bound is 0).
    let size = |t: f64| if t.is_finite() { t.abs() } else { 0.0 };
    let c = coincidence(size(a0).max(size(a1)).max(size(b0)).max(size(b1)), scale);
    let sep = |x: f64, y: f64| x.max(y) > x.min(y) + c;
    if !(sep(a0, b0) && sep(a0, b1) && sep(a1, b0) && sep(a1, b1)) {
        return None;
    }
    let one = |s: Span| Some(([s, s], 1));
    let span = |enter, exit| Span { enter, exit };
    match op {
        Op::Intersection => {
            let enter = if a0 > b0 { a.enter } else { b.enter };
            let exit = if a1 < b1 { a.exit } else { b.exit };
            if enter.t < exit.t {
                one(span(enter, exit))
            } else {
                Some(([*a, *a], 0))
            }
        }
        Op::Difference => {
            let (cut_in, cut_out) = (b.enter.flipped(), b.exit.flipped());
            match (b0 < a0, b1 < a1) {
                // B wholly before A, or B ends inside it.
                (true, true) if b1 < a0 => one(*a),
                (true, true) => one(span(cut_out, a.exit)),
                (true, false) => Some(([*a, *a], 0)),
                // B wholly after A, or B starts inside it.
                (false, false) if b0 > a1 => one(*a),
                (false, false) => one(span(a.enter, cut_in)),
                (false, true) => Some(([span(a.enter, cut_in), span(cut_out, a.exit)], 2)),
            }
        }
        Op::Union | Op::Xor => None,
    }
}

/// `a op b` written out when both lists hold one span ([`union_one`],
/// [`cut_one`]): up to two spans and how many, or `None` for the sweep.
/// For lists that [`quick`] left to the sweep (a union's not [`apart`]).
#[inline]
pub fn single(op: Op, a: &[Span], b: &[Span], scale: f64) -> Option<([Span; 2], usize)> {
    let ([x], [y]) = (a, b) else {
        return None;
    };
    if op == Op::Union {
        union_one(x, y, scale).map(|s| ([s, s], 1))
    } else {
        cut_one(op, x, y, scale)
    }
}

/// [`combine`], appending the result to `out`.
pub fn combine_into(op: Op, a: &[Span], b: &[Span], scale: f64, out: &mut Vec<Span>) {
    match quick(op, a, b, scale) {
        Some(Quick::A) => out.extend_from_slice(a),
        Some(Quick::B) => out.extend_from_slice(b),
        Some(Quick::Empty) => {}
        Some(Quick::AThenB) => {
            out.extend_from_slice(a);
            out.extend_from_slice(b);
        }
        Some(Quick::BThenA) => {
            out.extend_from_slice(b);
            out.extend_from_slice(a);
        }
        None => match single(op, a, b, scale) {
            Some((r, n)) => out.extend_from_slice(&r[..n]),
            None => sweep_into(op, a, b, scale, out),
        },
    }
}

/// `a op b` by one sweep over both lists, whatever they hold.
pub fn sweep_into(op: Op, a: &[Span], b: &[Span], scale: f64, out: &mut Vec<Span>) {
    let (mut ia, mut ib) = (0usize, 0usize);
    let (mut in_a, mut in_b) = (false, false);
    let mut inside = false;
    let mut enter = Boundary::open(f64::NEG_INFINITY);
    loop {
        let na = next(a, ia, in_a);
        let nb = next(b, ib, in_b);
        let t = match (na, nb) {
            (None, None) => break,
            (Some(x), None) => x.t,
            (None, Some(y)) => y.t,
            (Some(x), Some(y)) => x.t.min(y.t),
        };
        let near = t + coincidence(t, scale);
        let step_a = na.filter(|x| x.t <= near);
        let step_b = nb.filter(|y| y.t <= near);
        assert!(
            step_a.is_some() || step_b.is_some(),
            "span ends must be ordered numbers, found {na:?} and {nb:?}"
        );
        if step_a.is_some() {
            in_a = !in_a;
            if !in_a {
                ia += 1;
            }
        }
        if step_b.is_some() {
            in_b = !in_b;
            if !in_b {
                ib += 1;
            }
        }
        let now = op.apply(in_a, in_b);
        if now == inside {
            continue;
        }
        // Credit the boundary to the operand whose change alone moves the
        // result the same way, A first; if neither does, to A.
        let old_a = in_a ^ step_a.is_some();
        let old_b = in_b ^ step_b.is_some();
        let a_agrees = step_a.is_some() && op.apply(in_a, old_b) == now;
        let b_agrees = step_b.is_some() && op.apply(old_a, in_b) == now;
        let from_b = !a_agrees && (b_agrees || step_a.is_none());
        let mut bound = if from_b {
            let mut y = step_b.expect("B changed here");
            // A symmetric difference crosses B's surface the other way
            // where A holds the point.
            if op == Op::Difference || op == Op::Xor && in_b != now {
                y = y.flipped();
            }
            y
        } else {
            let x = step_a.expect("A changed here");
            if op == Op::Xor && in_a != now {
                x.flipped()
            } else {
                x
            }
        };
        bound.t = t;
        if now {
            enter = bound;
        } else {
            out.push(Span { enter, exit: bound });
        }
        inside = now;
        // Once both lists are exhausted and we are outside, we are done; for
        // an intersection or difference, running out of A ends everything.
        if ia >= a.len() && (!op.b_alone() || ib >= b.len()) && !inside {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn b(t: f64, prim: u32) -> Boundary {
        Boundary::new(t, prim, 0)
    }

    #[test]
    fn a_boundary_keeps_its_part_and_flip_apart() {
        for part in [0, 1, 5, 123_456_789, crate::geometry::NO_PART] {
            let x = Boundary::new(2.5, 7, part);
            assert_eq!((x.part(), x.flip()), (part, false));
            let y = x.flipped();
            assert_eq!((y.t, y.prim, y.part(), y.flip()), (2.5, 7, part, true));
            assert_eq!(y.flipped(), x);
        }
        assert_eq!(std::mem::size_of::<Boundary>(), 16);
    }

    /// A list from (enter, exit) pairs; A's surfaces are prim 0, B's prim 1.
    fn list(prim: u32, v: &[(f64, f64)]) -> Vec<Span> {
        v.iter()
            .map(|&(x, y)| Span {
                enter: b(x, prim),
                exit: b(y, prim),
            })
            .collect()
    }

    /// (enter t, enter prim, enter flip, exit t, exit prim, exit flip)
    type Row = (f64, u32, bool, f64, u32, bool);

    fn rows(l: &[Span]) -> Vec<Row> {
        l.iter()
            .map(|s| {
                (
                    s.enter.t,
                    s.enter.prim,
                    s.enter.flip(),
                    s.exit.t,
                    s.exit.prim,
                    s.exit.flip(),
                )
            })
            .collect()
    }

    fn check(op: Op, a: &[(f64, f64)], bb: &[(f64, f64)], want: &[Row]) {
        let got = combine(op, &list(0, a), &list(1, bb), 0.0);
        assert_eq!(rows(&got), want, "{op:?} of {a:?} and {bb:?}");
    }

    use Op::{Difference as D, Intersection as I, Union as U, Xor as X};
    const F: bool = false;
    const T: bool = true;

    #[test]
    fn disjoint() {
        let (a, bb) = (&[(0.0, 1.0)][..], &[(2.0, 3.0)][..]);
        check(U, a, bb, &[(0.0, 0, F, 1.0, 0, F), (2.0, 1, F, 3.0, 1, F)]);
        check(I, a, bb, &[]);
        check(D, a, bb, &[(0.0, 0, F, 1.0, 0, F)]);
        check(D, bb, a, &[(2.0, 0, F, 3.0, 0, F)]);
    }

    #[test]
    fn symmetric_difference() {
        // Overlapping: A's part before B, then B's after A, the surfaces
        // met from the other side flipped.
        check(
            X,
            &[(0.0, 2.0)],
            &[(1.0, 3.0)],
            &[(0.0, 0, F, 1.0, 1, T), (2.0, 0, T, 3.0, 1, F)],
        );
        // Nested: a shell.
        check(
            X,
            &[(0.0, 3.0)],
            &[(1.0, 2.0)],
            &[(0.0, 0, F, 1.0, 1, T), (2.0, 1, T, 3.0, 0, F)],
        );
        // Apart, touching, equal, empty.
        check(
            X,
            &[(0.0, 1.0)],
            &[(2.0, 3.0)],
            &[(0.0, 0, F, 1.0, 0, F), (2.0, 1, F, 3.0, 1, F)],
        );
        check(X, &[(0.0, 1.0)], &[(1.0, 2.0)], &[(0.0, 0, F, 2.0, 1, F)]);
        check(X, &[(0.0, 1.0)], &[(0.0, 1.0)], &[]);
        check(X, &[], &[(0.0, 1.0)], &[(0.0, 1, F, 1.0, 1, F)]);
    }

    #[test]
    fn touching() {
        let (a, bb) = (&[(0.0, 1.0)][..], &[(1.0, 2.0)][..]);
        check(U, a, bb, &[(0.0, 0, F, 2.0, 1, F)]);
        check(I, a, bb, &[]);
        check(D, a, bb, &[(0.0, 0, F, 1.0, 0, F)]);
        check(D, bb, a, &[(1.0, 0, F, 2.0, 0, F)]);
    }

    #[test]
    fn overlapping() {
        let (a, bb) = (&[(0.0, 2.0)][..], &[(1.0, 3.0)][..]);
        check(U, a, bb, &[(0.0, 0, F, 3.0, 1, F)]);
        check(I, a, bb, &[(1.0, 1, F, 2.0, 0, F)]);
        check(D, a, bb, &[(0.0, 0, F, 1.0, 1, T)]);
        // B − A: B's own surfaces keep their normals, A's are flipped.
        let got = combine(D, &list(1, bb), &list(0, a), 0.0);
        assert_eq!(rows(&got), vec![(2.0, 0, T, 3.0, 1, F)]);
    }

    #[test]
    fn nested() {
        let (a, bb) = (&[(0.0, 3.0)][..], &[(1.0, 2.0)][..]);
        check(U, a, bb, &[(0.0, 0, F, 3.0, 0, F)]);
        check(I, a, bb, &[(1.0, 1, F, 2.0, 1, F)]);
        check(D, a, bb, &[(0.0, 0, F, 1.0, 1, T), (2.0, 1, T, 3.0, 0, F)]);
        check(D, bb, a, &[]);
    }

    #[test]
    fn equal_endpoints() {
        // Identical spans: A − A is empty, A ∪ A and A ∩ A are A's.
        let a = &[(0.0, 1.0)][..];
        check(U, a, a, &[(0.0, 0, F, 1.0, 0, F)]);
        check(I, a, a, &[(0.0, 0, F, 1.0, 0, F)]);
        check(D, a, a, &[]);
        // Shared enter: the difference starts where B ends.
        check(D, &[(0.0, 2.0)], &[(0.0, 1.0)], &[(1.0, 1, T, 2.0, 0, F)]);
        // Shared exit: the difference ends where B starts.
        check(D, &[(0.0, 2.0)], &[(1.0, 2.0)], &[(0.0, 0, F, 1.0, 1, T)]);
        // Shared exit in an intersection is credited to A.
        check(I, &[(0.0, 2.0)], &[(1.0, 2.0)], &[(1.0, 1, F, 2.0, 0, F)]);
    }

    #[test]
    fn empty() {
        let a = &[(0.0, 1.0)][..];
        check(U, a, &[], &[(0.0, 0, F, 1.0, 0, F)]);
        check(U, &[], a, &[(0.0, 1, F, 1.0, 1, F)]);
        check(I, a, &[], &[]);
        check(I, &[], a, &[]);
        check(D, a, &[], &[(0.0, 0, F, 1.0, 0, F)]);
        check(D, &[], a, &[]);
        check(U, &[], &[], &[]);
    }

    #[test]
    fn many_spans() {
        let a = &[(0.0, 1.0), (2.0, 3.0), (4.0, 5.0), (6.0, 7.0)][..];
        let bb = &[(0.5, 2.5), (3.0, 4.0), (6.5, 9.0)][..];
        check(U, a, bb, &[(0.0, 0, F, 5.0, 0, F), (6.0, 0, F, 9.0, 1, F)]);
        check(
            I,
            a,
            bb,
            &[
                (0.5, 1, F, 1.0, 0, F),
                (2.0, 0, F, 2.5, 1, F),
                (6.5, 1, F, 7.0, 0, F),
            ],
        );
        check(
            D,
            a,
            bb,
            &[
                (0.0, 0, F, 0.5, 1, T),
                (2.5, 1, T, 3.0, 0, F),
                (4.0, 0, F, 5.0, 0, F),
                (6.0, 0, F, 6.5, 1, T),
            ],
        );
    }

    #[test]
    fn infinite_spans_combine_like_finite_ones() {
        let inf = f64::INFINITY;
        check(
            D,
            &[(-inf, inf)],
            &[(1.0, 2.0)],
            &[(-inf, 0, F, 1.0, 1, T), (2.0, 1, T, inf, 0, F)],
        );
    }

    /// Sorted, disjoint, non-touching span lists from sorted distinct cuts.
    fn arb_list() -> impl Strategy<Value = Vec<(f64, f64)>> {
        prop::collection::btree_set(0i32..40, 0..12).prop_map(|s| {
            let v: Vec<f64> = s.into_iter().map(|x| x as f64 * 0.5).collect();
            v.chunks_exact(2).map(|c| (c[0], c[1])).collect()
        })
    }

    fn arb_op() -> impl Strategy<Value = Op> {
        prop_oneof![Just(U), Just(I), Just(D), Just(X)]
    }

    /// Like [`arb_list`], but its spans may sit anywhere from -20 to 40, so
    /// that two lists often lie wholly apart.
    fn arb_shifted() -> impl Strategy<Value = Vec<(f64, f64)>> {
        (arb_list(), -40i32..40).prop_map(|(l, k)| {
            l.into_iter()
                .map(|(x, y)| (x + k as f64 * 0.5, y + k as f64 * 0.5))
                .collect()
        })
    }

    proptest! {
        /// The shortcuts give exactly what a sweep gives.
        #[test]
        fn shortcuts_agree_with_the_sweep(a in arb_shifted(), bb in arb_shifted(), op in arb_op(), scale in prop_oneof![Just(0.0), Just(1e3), Just(1e15)]) {
            let la = list(0, &a);
            let lb = list(1, &bb);
            let mut swept = Vec::new();
            sweep_into(op, &la, &lb, scale, &mut swept);
            prop_assert_eq!(combine(op, &la, &lb, scale), swept);
        }

        /// Two single spans whose ends fall on, within and just beyond the
        /// coincidence bound of one another: the union, intersection and
        /// difference written out give the sweep's spans, to the bit,
        /// credit and flips included (the union always, the others where
        /// they answer at all).
        #[test]
        fn single_spans_written_out_agree_with_the_sweep(
            ends in proptest::collection::vec((0usize..4, -3i32..=3), 4),
            scale in prop_oneof![Just(0.0), Just(1e3), Just(1e15)],
            infinite in 0usize..6,
        ) {
            // Ends near 0, 1, 2 or 3 (of the ray's scale), moved by whole
            // and half bounds.
            let unit = if scale == 0.0 { 1.0 } else { scale };
            let mut t: Vec<f64> = ends
                .iter()
                .map(|&(k, m)| {
                    let base = k as f64 * unit;
                    base + m as f64 * 0.5 * coincidence(base, scale)
                })
                .collect();
            t[..2].sort_by(f64::total_cmp);
            t[2..].sort_by(f64::total_cmp);
            // Sometimes an open end, as a half-space gives.
            match infinite {
                0 => t[0] = f64::NEG_INFINITY,
                1 => t[3] = f64::INFINITY,
                _ => {}
            }
            let a = list(0, &[(t[0], t[1])]);
            let bb = list(1, &[(t[2], t[3])]);
            for (x, y) in [(&a, &bb), (&bb, &a)] {
                for op in [U, I, D] {
                    let mut swept = Vec::new();
                    sweep_into(op, x, y, scale, &mut swept);
                    let got = if op == U {
                        if apart(x, y, scale).is_some() {
                            continue;
                        }
                        let s = union_one(&x[0], &y[0], scale);
                        prop_assert!(s.is_some(), "{:?} ∪ {:?}", x, y);
                        s.map(|s| vec![s])
                    } else {
                        cut_one(op, &x[0], &y[0], scale).map(|(r, n)| r[..n].to_vec())
                    };
                    if let Some(got) = got {
                        prop_assert_eq!(&got, &swept, "{:?} {:?} {:?}", x, op, y);
                    }
                    prop_assert_eq!(combine(op, x, y, scale), swept);
                }
            }
        }

        /// Membership of any t in `a op b` equals `op(member(a), member(b))`,
        /// tested at every endpoint's neighbourhood and between them (the
        /// endpoints themselves sit on the boundary, where either answer is
        /// a surface point).
        #[test]
        fn membership_agrees_with_the_operation(a in arb_list(), bb in arb_list(), op in arb_op()) {
            let la = list(0, &a);
            let lb = list(1, &bb);
            let r = combine(op, &la, &lb, 0.0);
            // The result is sorted, disjoint and has no empty spans.
            for w in r.windows(2) {
                prop_assert!(w[0].exit.t < w[1].enter.t);
            }
            for s in &r {
                prop_assert!(s.enter.t < s.exit.t);
            }
            for k in -2..84 {
                let t = k as f64 * 0.25 + 0.125;
                let want = op.apply(contains(&la, t), contains(&lb, t));
                prop_assert_eq!(contains(&r, t), want, "t = {}", t);
            }
        }

        /// Every boundary of the result is a boundary of an operand at the
        /// same t, credited to that operand.
        #[test]
        fn boundaries_come_from_the_operands(a in arb_list(), bb in arb_list(), op in arb_op()) {
            let la = list(0, &a);
            let lb = list(1, &bb);
            for s in combine(op, &la, &lb, 0.0) {
                for e in [s.enter, s.exit] {
                    let src = if e.prim == 0 { &la } else { &lb };
                    prop_assert!(src.iter().any(|x| x.enter.t == e.t || x.exit.t == e.t));
                    if op != X {
                        prop_assert_eq!(e.flip(), op == D && e.prim == 1);
                    }
                }
            }
        }

        /// The normal a boundary stands for points out of the result: its
        /// operand's own outward side (back along the line where the
        /// operand is entered, on where it is left), turned by the flip,
        /// is back at the result's enter and on at its exit.
        #[test]
        fn normals_point_out_of_the_result(a in arb_list(), bb in arb_list(), op in arb_op()) {
            let la = list(0, &a);
            let lb = list(1, &bb);
            for s in combine(op, &la, &lb, 0.0) {
                for (e, want) in [(s.enter, -1.0), (s.exit, 1.0)] {
                    let src = if e.prim == 0 { &la } else { &lb };
                    let own = if src.iter().any(|x| x.enter.t == e.t) { -1.0 } else { 1.0 };
                    let dir = if e.flip() { -own } else { own };
                    prop_assert_eq!(dir, want, "{:?} at t = {}", op, e.t);
                }
            }
        }
    }
}
