//! Real roots of polynomials of degree ≤ 6 inside an interval.
//!
//! No closed forms above degree 2: the roots of a polynomial's derivative
//! split the interval into pieces where it is monotonic, and each piece with
//! a sign change holds exactly one root, found by Newton steps safeguarded by
//! bisection. The derivative's roots are found the same way, down to a
//! quadratic, solved by the formula that does not cancel.
//! This is slower than Ferrari's formula but loses no roots to cancellation.

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
        3 => split_in::<3>(c, lo, hi, out),
        4 => split_in::<4>(c, lo, hi, out),
        5 => split_in::<5>(c, lo, hi, out),
        _ => split_in::<6>(c, lo, hi, out),
    }
}

/// [`roots_in`] of a polynomial of degree `D` ≥ 3 (`c[D]` not zero), each
/// degree compiled on its own so that every evaluation is unrolled.
#[inline(always)]
fn split_in<const D: usize>(c: &Poly, lo: f64, hi: f64, out: &mut Roots) -> usize {
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
            out[n] = refine::<D>(c, &d, a, b, fa);
            n += 1;
        }
        a = b;
        fa = fb;
    }
    n
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
/// sign: Newton steps, falling back to bisection when a step leaves the
/// bracket or does not shrink it fast enough.
fn refine<const D: usize>(c: &Poly, d: &Poly, mut a: f64, mut b: f64, fa: f64) -> f64 {
    let rising = fa < 0.0;
    let mut x = 0.5 * (a + b);
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
    fn roots_outside_the_interval_are_not_reported() {
        let c = from_roots(&[-1.0, 2.0, 30.0]);
        let mut out = [0.0; MAX_DEGREE];
        assert_eq!(roots_in(&c, 3, 0.0, 10.0, &mut out), 1);
        assert!((out[0] - 2.0).abs() < 1e-14);
    }
}
