//! Real roots of polynomials of degree ≤ 6 inside an interval.
//!
//! No closed forms above degree 2: the roots of a polynomial's derivative
//! split the interval into pieces where it is monotonic, and each piece with
//! a sign change holds exactly one root, found by Newton steps safeguarded by
//! bisection. The derivative's roots are found the same way, down to a
//! quadratic, solved by the formula that does not cancel.
//! This is slower than Ferrari's formula but loses no roots to cancellation;
//! a quartic's Newton steps may start from Ferrari's estimates
//! ([`quartic_estimates`], [`roots_in_from`]), which then only save steps.

/// The highest degree handled.
pub const MAX_DEGREE: usize = 6;

/// Coefficients, lowest degree first: `c[0] + c[1]·x + …`.
pub type Poly = [f64; MAX_DEGREE + 1];

/// Room for every root of a polynomial of [`MAX_DEGREE`].
pub type Roots = [f64; MAX_DEGREE];

/// A polynomial from its first coefficients (the rest zero).
pub fn poly(c: &[f64]) -> Poly {
    let mut p = [0.0; MAX_DEGREE + 1];
    p[..c.len()].copy_from_slice(c);
    p
}

pub fn eval(c: &[f64], degree: usize, x: f64) -> f64 {
    let mut v = c[degree];
    for i in (0..degree).rev() {
        v = v * x + c[i];
    }
    v
}

/// [`eval`] of a degree known when compiling: the same operations, unrolled.
#[inline(always)]
fn eval_n<const D: usize>(c: &Poly, x: f64) -> f64 {
    let mut v = c[D];
    for i in (0..D).rev() {
        v = v * x + c[i];
    }
    v
}

fn derivative(c: &Poly, degree: usize) -> Poly {
    let mut d = [0.0; MAX_DEGREE + 1];
    for i in 1..=degree {
        d[i - 1] = c[i] * i as f64;
    }
    d
}

/// The simple real roots of `c` (of the given degree) in `(lo, hi)`, sorted,
/// written to `out`; returns how many. Roots of even multiplicity (tangent
/// touches) do not change sign and are not reported.
pub fn roots_in(c: &Poly, degree: usize, lo: f64, hi: f64, out: &mut Roots) -> usize {
    roots_in_from(c, degree, lo, hi, &[], out)
}

/// [`roots_in`], each root's Newton steps starting from the first of
/// `starts` that lies inside its bracket (a closed form's estimate, say)
/// instead of the bracket's middle. The starts are not trusted: the roots are
/// isolated and bracketed as before, and a start outside every bracket is
/// not used. Only where the polynomial changes sign do they matter.
pub fn roots_in_from(
    c: &Poly,
    degree: usize,
    lo: f64,
    hi: f64,
    starts: &[f64],
    out: &mut Roots,
) -> usize {
    let mut degree = degree;
    while degree > 0 && c[degree] == 0.0 {
        degree -= 1;
    }
    match degree {
        0 => 0,
        1 => {
            let x = -c[0] / c[1];
            if x > lo && x < hi {
                out[0] = x;
                return 1;
            }
            0
        }
        2 => quadratic_in(c, lo, hi, out),
        3 => split_in::<3>(c, lo, hi, starts, out),
        4 => split_in::<4>(c, lo, hi, starts, out),
        5 => split_in::<5>(c, lo, hi, starts, out),
        _ => split_in::<6>(c, lo, hi, starts, out),
    }
}

/// [`roots_in`] of a polynomial of degree `D` ≥ 3 (`c[D]` not zero), each
/// degree compiled on its own so that every evaluation is unrolled.
#[inline(always)]
fn split_in<const D: usize>(c: &Poly, lo: f64, hi: f64, starts: &[f64], out: &mut Roots) -> usize {
    // Split (lo, hi) at the critical points.
    let d = derivative(c, D);
    let mut crit = [0.0; MAX_DEGREE];
    let nc = roots_in(&d, D - 1, lo, hi, &mut crit);
    let mut n = 0;
    let mut a = lo;
    let mut fa = eval_n::<D>(c, a);
    for (i, &b) in crit[..nc].iter().chain(std::iter::once(&hi)).enumerate() {
        let fb = eval_n::<D>(c, b);
        if fa == 0.0 && i > 0 {
            // A root exactly on a critical point is a multiple root: skip it.
        } else if (fa < 0.0) != (fb < 0.0) && fb != 0.0 && n < MAX_DEGREE {
            let x0 = match starts.iter().find(|&&x| x > a && x < b) {
                Some(&x) => x,
                None => 0.5 * (a + b),
            };
            out[n] = refine::<D>(c, &d, a, b, fa, x0);
            n += 1;
        }
        a = b;
        fa = fb;
    }
    n
}

/// Estimates of the real roots of the quartic `c` (`c[4]` not zero) by
/// Ferrari's closed form, unsorted, for [`roots_in_from`] to start from;
/// returns how many. Cancellation can make them poor, or lose a pair close
/// to a double root (then the bracket's middle is the start, as without).
pub fn quartic_estimates(c: &Poly, out: &mut [f64; 4]) -> usize {
    let inv = 1.0 / c[4];
    let (a, b, cc, d) = (c[3] * inv, c[2] * inv, c[1] * inv, c[0] * inv);
    // x = y − a/4: y⁴ + p y² + q y + r.
    let a2 = a * a;
    let p = b - 0.375 * a2;
    let q = cc - 0.5 * a * b + 0.125 * a2 * a;
    let r = d - 0.25 * a * cc + 0.0625 * a2 * b - 0.01171875 * a2 * a2;
    let shift = -0.25 * a;
    let mut n = 0;
    let mut push_quadratic = |lin: f64, k: f64, n: &mut usize| {
        // y² + lin·y + k = 0
        let disc = lin * lin - 4.0 * k;
        if disc >= 0.0 {
            let qq = -0.5 * (lin + disc.sqrt().copysign(lin));
            if qq != 0.0 {
                out[*n] = qq + shift;
                out[*n + 1] = k / qq + shift;
                *n += 2;
            }
        }
    };
    // The resolvent m³ + p m² + (p²/4 − r) m − q²/8 = 0 has a root m > 0
    // (it is −q²/8 ≤ 0 at 0): its largest, from the depressed cubic
    // (m = z − p/3) by Cardano's form where that has one real root, by
    // Newton from above where it has three.
    let (c2, c1, c0) = (p, 0.25 * p * p - r, -0.125 * q * q);
    let pp = c1 - c2 * c2 / 3.0;
    let qq = 2.0 * c2 * c2 * c2 / 27.0 - c2 * c1 / 3.0 + c0;
    let disc = 0.25 * qq * qq + pp * pp * pp / 27.0;
    let z = if disc < 0.0 {
        // Three real roots, the largest in [R, 2R] with R = √(−pp/3), where
        // the cubic rises and is convex (z > 0): Newton from 2R descends to
        // it without overshooting. A few steps give a start's accuracy.
        let rr = (-pp / 3.0).sqrt();
        let mut z = 2.0 * rr;
        for _ in 0..6 {
            let f = (z * z + pp) * z + qq;
            let step = f / (3.0 * z * z + pp);
            z -= step;
            if step <= 1e-9 * z {
                break;
            }
        }
        z
    } else {
        let s = disc.sqrt();
        cbrt_estimate(-0.5 * qq + s) + cbrt_estimate(-0.5 * qq - s)
    };
    let m = z - c2 / 3.0;
    if m > 0.0 {
        let sq = (2.0 * m).sqrt();
        let h = 0.5 * q / sq;
        push_quadratic(-sq, 0.5 * p + m + h, &mut n);
        push_quadratic(sq, 0.5 * p + m - h, &mut n);
    } else {
        // q ≈ 0: a quadratic in y².
        let disc = p * p - 4.0 * r;
        if disc >= 0.0 {
            let s = disc.sqrt();
            for y2 in [0.5 * (-p + s), 0.5 * (-p - s)] {
                if y2 >= 0.0 {
                    let y = y2.sqrt();
                    out[n] = y + shift;
                    out[n + 1] = -y + shift;
                    n += 2;
                }
            }
        }
    }
    n
}

/// The cube root to about 1e-12 (relative): an exponent-thirding guess off
/// the bits (a few per cent) and two Halley steps. For starts only: a tenth
/// of the cost of `f64::cbrt`, which is software here.
fn cbrt_estimate(x: f64) -> f64 {
    let ax = x.abs();
    if ax == 0.0 || !ax.is_finite() {
        return x;
    }
    let mut y = f64::from_bits(ax.to_bits() / 3 + 0x2A9F_7893_782D_A1CE);
    for _ in 0..2 {
        let y3 = y * y * y;
        y *= (y3 + 2.0 * ax) / (2.0 * y3 + ax);
    }
    y.copysign(x)
}

/// The simple roots of the quadratic `c` in `(lo, hi)`, sorted, by the
/// formula that does not cancel: q = −(b + sign(b)·√disc)/2, roots q/a and
/// c/q. A double root (disc = 0) touches without crossing: none.
fn quadratic_in(c: &Poly, lo: f64, hi: f64, out: &mut Roots) -> usize {
    let (a, b, k) = (c[2], c[1], c[0]);
    let disc = b * b - 4.0 * a * k;
    if disc <= 0.0 || !disc.is_finite() {
        return 0;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (x0, x1) = (q / a, k / q);
    let (x0, x1) = if x0 <= x1 { (x0, x1) } else { (x1, x0) };
    let mut n = 0;
    for x in [x0, x1] {
        if x > lo && x < hi {
            out[n] = x;
            n += 1;
        }
    }
    n
}

/// The one root in `[a, b]`, where the polynomial is monotonic and changes
/// sign: Newton steps from `x0` (inside the bracket), falling back to
/// bisection when a step leaves the bracket or does not shrink it fast
/// enough.
fn refine<const D: usize>(c: &Poly, d: &Poly, mut a: f64, mut b: f64, fa: f64, x0: f64) -> f64 {
    let rising = fa < 0.0;
    let mut x = x0;
    for _ in 0..200 {
        let f = eval_n::<D>(c, x);
        if f == 0.0 {
            return x;
        }
        if (f < 0.0) == rising {
            a = x;
        } else {
            b = x;
        }
        let df = eval_n_minus_1::<D>(d, x);
        let newton = x - f / df;
        let next = if newton > a && newton < b && df != 0.0 {
            newton
        } else {
            0.5 * (a + b)
        };
        // The larger end by a plain select, not f64::max, whose care for
        // NaN sat in every step (3.7 % of nested_tori's instructions): the
        // same value unless an end is NaN, and then b − a is NaN too and
        // the test fails either way.
        let (ma, mb) = (a.abs(), b.abs());
        let wide = if ma > mb { ma } else { mb };
        if (next - x).abs() <= 2.0 * f64::EPSILON * x.abs() || b - a <= f64::EPSILON * wide {
            return next;
        }
        x = next;
    }
    x
}

/// [`eval`] of the derivative of a polynomial of degree `D`.
#[inline(always)]
fn eval_n_minus_1<const D: usize>(d: &Poly, x: f64) -> f64 {
    let mut v = d[D - 1];
    for i in (0..D - 1).rev() {
        v = v * x + d[i];
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn from_roots(r: &[f64]) -> Poly {
        let mut c = [0.0; MAX_DEGREE + 1];
        c[0] = 1.0;
        for (deg, &x) in r.iter().enumerate() {
            // multiply by (t - x)
            let mut n = [0.0; MAX_DEGREE + 1];
            for i in 0..=deg {
                n[i + 1] += c[i];
                n[i] -= x * c[i];
            }
            c = n;
        }
        c
    }

    #[test]
    fn finds_four_close_roots_of_a_quartic() {
        let r = [0.1, 0.1001, 3.0, 7.5];
        let c = from_roots(&r);
        let mut out = [0.0; MAX_DEGREE];
        let n = roots_in(&c, 4, 0.0, 10.0, &mut out);
        assert_eq!(n, 4);
        for i in 0..4 {
            assert!((out[i] - r[i]).abs() < 1e-12, "{out:?}");
        }
    }

    #[test]
    fn a_double_root_is_a_touch_not_a_crossing() {
        let c = from_roots(&[1.0, 1.0, 4.0, 5.0]);
        let mut out = [0.0; MAX_DEGREE];
        let n = roots_in(&c, 4, 0.0, 10.0, &mut out);
        assert_eq!(n, 2, "{out:?}");
        assert!((out[0] - 4.0).abs() < 1e-12 && (out[1] - 5.0).abs() < 1e-12);
    }

    #[test]
    fn finds_the_roots_of_a_sextic() {
        let r = [-0.3, 0.05, 0.0501, 0.7, 1.9, 2.0];
        let c = from_roots(&r);
        let mut out = [0.0; MAX_DEGREE];
        let n = roots_in(&c, 6, -1.0, 3.0, &mut out);
        assert_eq!(n, 6, "{out:?}");
        for i in 0..6 {
            assert!((out[i] - r[i]).abs() < 1e-12, "{out:?}");
        }
    }

    #[test]
    fn ferrari_estimates_are_close_to_separated_roots() {
        for r in [
            [0.5, 1.25, 2.0, 3.5],
            [-3.0, -0.1, 0.2, 9.0],
            [0.30, 0.31, 1.7, 1.8],
        ] {
            let c = from_roots(&r);
            let mut est = [0.0; 4];
            assert_eq!(quartic_estimates(&c, &mut est), 4, "{r:?}");
            est.sort_by(f64::total_cmp);
            for i in 0..4 {
                assert!((est[i] - r[i]).abs() < 1e-9, "{r:?}: {est:?}");
            }
        }
        // Two real roots and a complex pair (x² + 1)(x − 1)(x − 4): two.
        let c = poly(&[4.0, -5.0, 5.0, -5.0, 1.0]);
        let mut est = [0.0; 4];
        assert_eq!(quartic_estimates(&c, &mut est), 2);
        est[..2].sort_by(f64::total_cmp);
        assert!(
            (est[0] - 1.0).abs() < 1e-9 && (est[1] - 4.0).abs() < 1e-9,
            "{est:?}"
        );
    }

    #[test]
    fn the_cube_root_estimate_is_close() {
        for &x in &[1e-30, 3e-7, 0.001, 0.5, 1.0, 2.0, 27.0, 1234.5, 7e22, 1e300] {
            for x in [x, -x] {
                let (e, c) = (cbrt_estimate(x), x.cbrt());
                assert!((e - c).abs() <= 1e-12 * c.abs(), "{x}: {e} against {c}");
            }
        }
        assert_eq!(cbrt_estimate(0.0), 0.0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Starts are hints only: any starts, however wrong (another root,
        /// a point outside every bracket, the interval's ends), give the
        /// roots that no starts give.
        #[test]
        fn starts_do_not_change_which_roots_are_found(
            r in proptest::collection::vec(-5.0f64..5.0, 4),
            junk in proptest::collection::vec(-8.0f64..8.0, 0..4),
            shift in 0usize..4,
        ) {
            let mut r = r;
            r.sort_by(f64::total_cmp);
            prop_assume!(r.windows(2).all(|w| w[1] - w[0] > 1e-3));
            let c = from_roots(&r);
            let (lo, hi) = (-6.0, 6.0);
            let mut want = [0.0; MAX_DEGREE];
            let n = roots_in(&c, 4, lo, hi, &mut want);
            prop_assert_eq!(n, 4);
            // The roots themselves, each put first where it is another
            // bracket's, and the junk.
            let mut starts: Vec<f64> = (0..4).map(|i| r[(i + shift) % 4]).collect();
            starts.extend(junk);
            starts.extend([lo, hi]);
            let mut got = [0.0; MAX_DEGREE];
            prop_assert_eq!(roots_in_from(&c, 4, lo, hi, &starts, &mut got), n);
            for i in 0..n {
                prop_assert!((got[i] - want[i]).abs() <= 1e-9 * (1.0 + want[i].abs()),
                    "{:?} against {:?}", &got[..n], &want[..n]);
            }
        }
    }

    #[test]
    fn roots_outside_the_interval_are_not_reported() {
        let c = from_roots(&[-1.0, 2.0, 30.0]);
        let mut out = [0.0; MAX_DEGREE];
        assert_eq!(roots_in(&c, 3, 0.0, 10.0, &mut out), 1);
        assert!((out[0] - 2.0).abs() < 1e-14);
    }
}
