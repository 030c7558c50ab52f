//! The sign changes of a trigonometric polynomial along a line, with
//! guaranteed isolation: the sides of twisted extrusions.
//!
//! A twisted side is met where
//!
//!   G(t) = A(t)·cos φ + B(t)·sin φ − C(t) [+ A₂(t)·cos 2φ + B₂(t)·sin 2φ],
//!
//! φ = φ₀ + φ₁·t, the coefficients polynomials of degree ≤ 4 (a polygon's
//! edge needs quadratics and the first harmonic; an ellipse, or a circle
//! scaled unevenly, quartics and the second). Its roots are isolated with
//! guaranteed bounds: over an interval of half-width r about m,
//! |G − G(m)| ≤ r·max|G′| and |G′ − G′(m)| ≤ r·max|G″| (the maxima from the
//! polynomials' ranges and |cos|, |sin| ≤ 1), so an interval is dropped
//! when |G(m)| > r·max|G′|, holds exactly one root when G′ keeps its sign
//! and G changes sign, and is halved otherwise (at most 60 times); the root
//! is then bisected to the last bit.

use crate::math::poly;

/// Coefficients up to degree 4, lowest first.
type Quartic = [f64; 5];
use smallvec::SmallVec;

/// A polynomial of degree ≤ 4, `c[0] + c[1]·t + …`, kept at a fixed degree
/// (a quadratic evaluates as `(c₂t + c₁)t + c₀` whatever its coefficients).
#[derive(Clone, Copy, Debug)]
pub struct Pol {
    pub c: Quartic,
    pub deg: usize,
}

impl Pol {
    pub fn quad(c: [f64; 3]) -> Pol {
        Pol {
            c: [c[0], c[1], c[2], 0.0, 0.0],
            deg: 2,
        }
    }

    /// `a·b` of two linear factors (a quadratic).
    pub fn mul_lin(a: [f64; 2], b: [f64; 2]) -> Pol {
        Pol::quad([a[0] * b[0], a[0] * b[1] + a[1] * b[0], a[1] * b[1]])
    }

    /// The product, of degree the sum of the degrees (≤ 4).
    pub fn mul(&self, o: &Pol) -> Pol {
        let deg = self.deg + o.deg;
        debug_assert!(deg <= 4);
        let mut c = [0.0; 5];
        for i in 0..=self.deg {
            for j in 0..=o.deg {
                c[i + j] += self.c[i] * o.c[j];
            }
        }
        Pol { c, deg }
    }

    /// u·p + v·q (of the larger degree).
    pub fn comb(p: Pol, q: Pol, u: f64, v: f64) -> Pol {
        let mut c = [0.0; 5];
        for (i, x) in c.iter_mut().enumerate() {
            *x = u * p.c[i] + v * q.c[i];
        }
        Pol {
            c,
            deg: p.deg.max(q.deg),
        }
    }

    /// k·p.
    pub fn scaled(&self, k: f64) -> Pol {
        Pol {
            c: self.c.map(|x| k * x),
            deg: self.deg,
        }
    }

    pub fn at(&self, t: f64) -> f64 {
        poly::eval(&self.c, self.deg, t)
    }

    fn derivative(&self) -> Pol {
        let mut c = [0.0; 5];
        for i in 1..=self.deg {
            c[i - 1] = i as f64 * self.c[i];
        }
        Pol {
            c,
            deg: self.deg.saturating_sub(1),
        }
    }

    fn d(&self, t: f64) -> f64 {
        if self.deg == 2 {
            2.0 * self.c[2] * t + self.c[1]
        } else {
            self.derivative().at(t)
        }
    }

    /// The largest |p| over [l, h]: exact at a quadratic's ends and vertex;
    /// above, the Taylor bound Σ |p⁽ᵏ⁾(m)/k!|·rᵏ about the middle.
    pub fn max_abs(&self, l: f64, h: f64) -> f64 {
        if self.deg <= 2 {
            let mut m = self.at(l).abs().max(self.at(h).abs());
            if self.c[2] != 0.0 {
                let v = -self.c[1] / (2.0 * self.c[2]);
                if v > l && v < h {
                    m = m.max(self.at(v).abs());
                }
            }
            return m;
        }
        let (m, r) = (0.5 * (l + h), 0.5 * (h - l));
        let b = self.shifted(m);
        (0..=self.deg)
            .rev()
            .fold(0.0, |acc, k| acc * r + b[k].abs())
    }

    /// The largest |p′| over [l, h].
    fn max_abs_d(&self, l: f64, h: f64) -> f64 {
        if self.deg <= 2 {
            self.d(l).abs().max(self.d(h).abs())
        } else {
            self.derivative().max_abs(l, h)
        }
    }

    /// The largest |p″| over [l, h].
    fn max_abs_dd(&self, l: f64, h: f64) -> f64 {
        if self.deg <= 2 {
            (2.0 * self.c[2]).abs()
        } else {
            self.derivative().derivative().max_abs(l, h)
        }
    }

    /// The coefficients of p(m + x) in x (a Taylor shift).
    fn shifted(&self, m: f64) -> Quartic {
        let mut b = self.c;
        for i in 0..self.deg {
            for j in (i..self.deg).rev() {
                b[j] += m * b[j + 1];
            }
        }
        b
    }
}

/// The most intervals one `Trig::roots_after` call examines: a bound on its work
/// whatever G is (the depth bound alone allows 2⁶⁰ of them), 46 times the
/// most any call of the example scenes' twisted extrusions took (1,421, in
/// tests/openscad/twisted_circles.csg at 320×240; most take under 100).
const ISOLATE_BUDGET: u32 = 1 << 16;

/// G(t) = A cos φ + B sin φ − C [+ A₂ cos 2φ + B₂ sin 2φ], φ = φ₀ + φ₁·t.
pub struct Trig {
    pub a: Pol,
    pub b: Pol,
    pub c: Pol,
    /// The second harmonic's A₂, B₂, when there is one.
    pub second: Option<(Pol, Pol)>,
    pub phi: [f64; 2],
}

/// φ's sines and cosines at one t: (sin φ, cos φ), and (sin 2φ, cos 2φ)
/// where G has a second harmonic.
struct Turn {
    first: (f64, f64),
    second: Option<(f64, f64)>,
}

/// What [`Trig::isolate`] knows of G over an interval before it asks for
/// G″'s bound: a bound of |G′|, the rounding's slack, and the
/// coefficients' largest magnitudes and slopes (A, B; A₂, B₂).
struct Maxima {
    m1: f64,
    slack: f64,
    first: [f64; 4],
    second: Option<[f64; 4]>,
}

impl Trig {
    pub fn g(&self, t: f64) -> f64 {
        self.g_at(&self.turn(t), t)
    }

    /// φ's sines and cosines at `t` (of 2φ too where there is a second
    /// harmonic): what G and G′ at `t` share.
    fn turn(&self, t: f64) -> Turn {
        let phi = self.phi[0] + self.phi[1] * t;
        Turn {
            first: phi.sin_cos(),
            second: self.second.as_ref().map(|_| (2.0 * phi).sin_cos()),
        }
    }

    /// G at `t`, φ's sines and cosines there given.
    fn g_at(&self, turn: &Turn, t: f64) -> f64 {
        let (s, c) = turn.first;
        let v = self.a.at(t) * c + self.b.at(t) * s - self.c.at(t);
        match (&self.second, turn.second) {
            (Some((a2, b2)), Some((s2, c2))) => v + (a2.at(t) * c2 + b2.at(t) * s2),
            _ => v,
        }
    }

    /// G′ at `t`, φ's sines and cosines there given.
    fn g1_at(&self, turn: &Turn, t: f64) -> f64 {
        let (s, c) = turn.first;
        let w = self.phi[1];
        let v = self.a.d(t) * c + self.b.d(t) * s + w * (self.b.at(t) * c - self.a.at(t) * s)
            - self.c.d(t);
        match (&self.second, turn.second) {
            (Some((a2, b2)), Some((s2, c2))) => {
                v + (a2.d(t) * c2 + b2.d(t) * s2 + 2.0 * w * (b2.at(t) * c2 - a2.at(t) * s2))
            }
            _ => v,
        }
    }

    /// The coefficients' largest magnitudes over [l, h], and from them
    /// the scale of G's own rounding there (their sum) and a bound of |G′|.
    fn maxima(&self, l: f64, h: f64) -> Maxima {
        let w = self.phi[1].abs();
        let (a0, b0, c0) = (
            self.a.max_abs(l, h),
            self.b.max_abs(l, h),
            self.c.max_abs(l, h),
        );
        let (a1, b1) = (self.a.max_abs_d(l, h), self.b.max_abs_d(l, h));
        let mut size = a0 + b0 + c0;
        let mut m1 = a1 + b1 + w * (a0 + b0) + self.c.max_abs_d(l, h);
        let mut second = None;
        if let Some((p, q)) = &self.second {
            // d/dt of A₂ cos 2φ: A₂′ cos 2φ − 2φ₁ A₂ sin 2φ, and so on.
            let (p0, q0) = (p.max_abs(l, h), q.max_abs(l, h));
            let (p1, q1) = (p.max_abs_d(l, h), q.max_abs_d(l, h));
            size += p0 + q0;
            m1 += p1 + q1 + 2.0 * w * (p0 + q0);
            second = Some([p0, q0, p1, q1]);
        }
        // Room for the rounding of G's own evaluation.
        let slack = 1e-13 * size;
        Maxima {
            m1: m1 * (1.0 + 1e-12) + slack,
            slack,
            first: [a0, b0, a1, b1],
            second,
        }
    }

    /// A bound of |G″| over [l, h], from [`Trig::maxima`]'s of the same
    /// interval.
    fn bound2(&self, l: f64, h: f64, k: &Maxima) -> f64 {
        let w = self.phi[1].abs();
        let [a0, b0, a1, b1] = k.first;
        let (a2, b2) = (self.a.max_abs_dd(l, h), self.b.max_abs_dd(l, h));
        let mut m2 = a2 + b2 + 2.0 * w * (a1 + b1) + w * w * (a0 + b0) + self.c.max_abs_dd(l, h);
        if let (Some((p, q)), Some([p0, q0, p1, q1])) = (&self.second, k.second) {
            let (p2, q2) = (p.max_abs_dd(l, h), q.max_abs_dd(l, h));
            m2 += p2 + q2 + 4.0 * w * (p1 + q1) + 4.0 * w * w * (p0 + q0);
        }
        m2 * (1.0 + 1e-12) + k.slack
    }

    /// The roots of G in [l, h) where it changes sign, appended to `out`,
    /// of the intervals `may` says may hold a root wanted (the caller's own
    /// bound: where a twisted side's point may lie on its edge; `|_, _|
    /// true` for all). An interval `may` refuses is dropped with what lies
    /// in it, before G is evaluated there; the others are halved and
    /// bisected as they would be without it, so every root found in them
    /// has the same bits. G(l) is `gl` where the caller knows it (`None`:
    /// found here); G(h) is returned where it was found (`None` where
    /// `may` refused the interval), for the interval that begins at h.
    pub fn roots_after(
        &self,
        l: f64,
        h: f64,
        gl: Option<f64>,
        may: &impl Fn(f64, f64) -> bool,
        out: &mut SmallVec<[f64; 8]>,
    ) -> Option<f64> {
        if !may(l, h) {
            return None;
        }
        let (gl, gh) = (gl.unwrap_or_else(|| self.g(l)), self.g(h));
        let mut budget = ISOLATE_BUDGET;
        self.isolate(l, h, gl, gh, 0, &mut budget, may, out);
        Some(gh)
    }

    #[allow(clippy::too_many_arguments)]
    fn isolate(
        &self,
        l: f64,
        h: f64,
        gl: f64,
        gh: f64,
        depth: u32,
        budget: &mut u32,
        may: &impl Fn(f64, f64) -> bool,
        out: &mut SmallVec<[f64; 8]>,
    ) {
        if !may(l, h) {
            return;
        }
        *budget = budget.saturating_sub(1);
        let (m, r) = (0.5 * (l + h), 0.5 * (h - l));
        let turn = self.turn(m);
        let gm = self.g_at(&turn, m);
        let k = self.maxima(l, h);
        let slack = k.slack;
        if gm.abs() > r * k.m1 + slack && (gl > 0.0) == (gm > 0.0) && (gh > 0.0) == (gm > 0.0) {
            return;
        }
        let changes = (gl > 0.0) != (gh > 0.0);
        let g1 = self.g1_at(&turn, m);
        let m2 = self.bound2(l, h, &k);
        // G no larger than its own rounding at both ends and the middle,
        // and its slope there no more: the line runs along the surface
        // (a side's function zero all along it), where halving finds
        // nothing but the rounding's signs.
        let flat = gl.abs().max(gm.abs()).max(gh.abs()) <= slack && (g1 * r).abs() <= slack;
        if flat || g1.abs() > r * m2 || depth >= 60 || *budget == 0 || m <= l || m >= h {
            // Monotone (or as narrow as it gets): one root if G changes sign.
            if changes {
                out.push(self.bisect(l, h, gl, gh));
            }
            return;
        }
        self.isolate(l, m, gl, gm, depth + 1, budget, may, out);
        self.isolate(m, h, gm, gh, depth + 1, budget, may, out);
    }

    /// The sign change of G in [l, h] (G(l) = `gl`, G(h) = `gh`, of
    /// opposite signs), to the last bit: the Illinois method, which keeps
    /// the sign change bracketed as bisection does but takes the secant's
    /// point (the value at an end kept twice halved), a bisection step
    /// where that point is not strictly inside. It ends as bisection ends,
    /// when the bracket's middle is one of its ends.
    fn bisect(&self, mut l: f64, mut h: f64, mut gl: f64, mut gh: f64) -> f64 {
        let left = gl > 0.0;
        let mut kept = 0i8;
        let steps = if crate::mutant::active("trig_roots_early") {
            3
        } else {
            200
        };
        for _ in 0..steps {
            let mid = 0.5 * (l + h);
            if mid <= l || mid >= h {
                break;
            }
            let secant = (l * gh - h * gl) / (gh - gl);
            let m = if secant > l && secant < h {
                secant
            } else {
                mid
            };
            let gm = self.g(m);
            if (gm > 0.0) == left {
                (l, gl) = (m, gm);
                if kept == 1 {
                    gh *= 0.5;
                }
                kept = 1;
            } else {
                (h, gh) = (m, gm);
                if kept == -1 {
                    gl *= 0.5;
                }
                kept = -1;
            }
        }
        0.5 * (l + h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taylor_bounds_hold_over_the_interval() {
        // p(t) = (t − 0.3)(t + 1.2)(t − 2)(3t − 0.7), sampled densely.
        let p = Pol::mul_lin([-0.3, 1.0], [1.2, 1.0]).mul(&Pol::mul_lin([-2.0, 1.0], [-0.7, 3.0]));
        for &(l, h) in &[(-2.0, 3.0), (0.1, 0.2), (-1e3, 1e3), (5.0, 5.0 + 1e-9)] {
            let (b0, b1, b2) = (p.max_abs(l, h), p.max_abs_d(l, h), p.max_abs_dd(l, h));
            let (d1, d2) = (p.derivative(), p.derivative().derivative());
            for i in 0..=1000 {
                let t = l + (h - l) * i as f64 / 1000.0;
                assert!(p.at(t).abs() <= b0 * (1.0 + 1e-12), "{t}");
                assert!(d1.at(t).abs() <= b1 * (1.0 + 1e-12), "{t}");
                assert!(d2.at(t).abs() <= b2 * (1.0 + 1e-12), "{t}");
            }
        }
    }

    #[test]
    fn second_harmonic_roots_are_all_found() {
        // G(t) = cos 2φ − 0.2 with φ = 3t over [0, 4]: roots where
        // 6t = ±acos(0.2) + 2πk.
        let zero = Pol::quad([0.0; 3]);
        let g = Trig {
            a: zero,
            b: zero,
            c: Pol::quad([0.2, 0.0, 0.0]),
            second: Some((Pol::quad([1.0, 0.0, 0.0]), zero)),
            phi: [0.0, 3.0],
        };
        let mut out = SmallVec::new();
        let mut l = 0.0;
        while l < 4.0 {
            g.roots_after(l, (l + 1.0 / 3.0).min(4.0), None, &|_, _| true, &mut out);
            l += 1.0 / 3.0;
        }
        let a = 0.2f64.acos();
        let mut want: Vec<f64> = (0..5)
            .flat_map(|k| {
                let base = 2.0 * std::f64::consts::PI * k as f64;
                [(base + a) / 6.0, (base - a) / 6.0]
            })
            .filter(|&t| t > 0.0 && t < 4.0)
            .collect();
        want.sort_by(f64::total_cmp);
        out.sort_by(f64::total_cmp);
        out.dedup();
        assert_eq!(out.len(), want.len(), "{out:?} {want:?}");
        for (x, y) in out.iter().zip(&want) {
            assert!((x - y).abs() < 1e-14, "{x} {y}");
        }
    }
}
