//! The torus around the z axis with major radius 1 and tube radius `minor`:
//! `torus(R, r)` is this solid scaled by R, with minor = r/R.
//!
//! (|p|² + 1 − r²)² − 4(x² + y²) = 0 is a quartic in t. As POV-Ray does, the
//! ray origin is first moved to where the line enters the torus's box and
//! the direction made unit, which keeps the coefficients small; the roots
//! are then isolated and polished by [`crate::math::poly::roots_in_from`], its
//! Newton steps starting from Ferrari's closed form (a guarded start: a root
//! is still only accepted inside a bracket where the quartic changes sign).

use super::solid::{spans_between_roots, Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::math::poly::{eval, quartic_estimates, roots_in_from, Poly};
use glam::{DAffine3, DVec3};

/// A torus around the z axis, major radius 1, tube radius `minor` > 0.
/// With `minor` ≥ 1 (a horn or spindle torus: OpenSCAD's turn of a circle
/// that reaches or crosses the axis, cut back to x ≥ 0 by a combination)
/// the solid is the outer "apple", (ρ − 1)² + z² ≤ r² — the turn of the
/// disc's part at x ≥ 0; the quartic's other factor, the inner "lemon"
/// (ρ + 1)² + z² = r², lies inside it and its roots are passed over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus {
    pub minor: f64,
}

impl Solid for Torus {
    const NAME: &'static str = "torus";

    #[inline]
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        spans(self.minor, q.o, q.d, emit)
    }

    fn normal(&self, p: DVec3, _part: Part) -> DVec3 {
        normal(p)
    }

    fn contains(&self, p: DVec3) -> bool {
        let q = p.truncate().length() - 1.0;
        q * q + p.z * p.z <= self.minor * self.minor
    }

    fn object_bounds(&self) -> Aabb {
        let e = DVec3::new(1.0 + self.minor, 1.0 + self.minor, self.minor);
        Aabb::new(-e, e)
    }

    /// The torus is the core circle ⊕ a ball of radius `minor`, and a
    /// linear map keeps Minkowski sums: the half-extents add, the
    /// ellipse's √(u² + v²) and the ellipsoid's minor·|row|.
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        let col = |i: usize| m.matrix3.col(i);
        let (u, v, w) = (col(0), col(1), col(2));
        let e = (u * u + v * v).powf(0.5) + self.minor * (u * u + v * v + w * w).powf(0.5);
        Aabb::new(m.translation - e, m.translation + e)
    }

    /// Of its hull: the core circle's support plus the ball's.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let flat = d.truncate();
        let ring = if flat == glam::DVec2::ZERO {
            DVec3::X
        } else {
            flat.normalize().extend(0.0)
        };
        Some(ring + self.minor * d.normalize())
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("major", Param::Num(1.0)),
            ("minor", Param::Num(self.minor)),
        ]
    }

    fn pov(&self) -> String {
        format!("torus {{ 1, {:?} rotate x*90", self.minor)
    }
}

pub fn spans(minor: f64, o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    // Clip the line to the box [-(1+r), 1+r]² × [-r, r].
    let e = DVec3::new(1.0 + minor, 1.0 + minor, minor);
    // Plain selects rather than f64::min and max, whose care for NaN cost
    // some 40 instructions a call (4 % of nested_tori's): the same ends for
    // any numbers (a zero's sign aside, which no use below can see), and a
    // NaN end fails both comparisons and is passed over, as max and min do.
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..3 {
        if d[i] == 0.0 {
            if o[i].abs() >= e[i] {
                return;
            }
        } else {
            let a = (-e[i] - o[i]) / d[i];
            let b = (e[i] - o[i]) / d[i];
            let (near, far) = if a < b { (a, b) } else { (b, a) };
            if near > lo {
                lo = near;
            }
            if far < hi {
                hi = far;
            }
        }
    }
    if lo >= hi {
        return;
    }
    // Local unit-speed parameter s = (t − lo)·|d| from the box entry.
    let len = d.length();
    let u = d / len;
    let p = o + lo * d;
    let span = (hi - lo) * len;
    let k = 1.0 - minor * minor;
    let b = p.dot(u);
    let c = p.length_squared() + k;
    let bxy = p.x * u.x + p.y * u.y;
    let axy = u.x * u.x + u.y * u.y;
    let cxy = p.x * p.x + p.y * p.y;
    // The solid lies where 1 − r ≤ ρ ≤ 1 + r (ρ the distance from the
    // axis). ρ² along the clipped segment is a convex quadratic: if even
    // its largest value (at an end) is inside the hole, or its smallest
    // beyond the rim, the line misses, with no quartic to solve. Through
    // the hole of a ring seen face on, this is most rays.
    let rho2 = |s: f64| cxy + s * (2.0 * bxy + s * axy);
    // (No hole when the tube reaches the axis.)
    let inner = if minor < 1.0 {
        (1.0 - minor) * (1.0 - minor)
    } else {
        0.0
    };
    let outer = (1.0 + minor) * (1.0 + minor);
    // The vertex clamped to [0, span], by selects as above.
    let s_min = if axy > 0.0 {
        let v = -bxy / axy;
        if v > span {
            span
        } else if v > 0.0 {
            v
        } else {
            0.0
        }
    } else {
        0.0
    };
    let (r0, r1) = (rho2(0.0), rho2(span));
    let rho2_max = if r0 > r1 { r0 } else { r1 };
    // A margin of a few ulps keeps grazing rays for the exact test.
    let margin = 1e-12;
    if rho2_max < inner * (1.0 - margin) || rho2(s_min) > outer * (1.0 + margin) {
        return;
    }
    // (s² + 2b s + c)² − 4(axy s² + 2 bxy s + cxy), |u| = 1.
    let poly: Poly = crate::math::poly::poly(&[
        c * c - 4.0 * cxy,
        4.0 * b * c - 8.0 * bxy,
        4.0 * b * b + 2.0 * c - 4.0 * axy,
        4.0 * b,
        1.0,
    ]);
    let mut roots = [0.0; crate::math::poly::MAX_DEGREE];
    let mut starts = [0.0; 4];
    let ns = quartic_estimates(&poly, &mut starts);
    let n = roots_in_from(&poly, 4, 0.0, span, &starts[..ns], &mut roots);
    // The box ends are outside the torus; spans are where the quartic < 0
    // (the apple's own test past the horn: a root on the lemon inside it
    // changes nothing).
    let apple = minor >= 1.0 && !crate::mutant::active("spindle_lemon_kept");
    let inside_at = |s: f64| {
        if apple {
            let q = p + s * u;
            q.length_squared() + k - 2.0 * q.truncate().length() < 0.0
        } else {
            eval(&poly, 4, s) < 0.0
        }
    };
    spans_between_roots(&roots[..n], (span, lo, hi, len), inside_at, emit);
}

pub fn normal(p: DVec3) -> DVec3 {
    let rho = p.truncate().length();
    if rho == 0.0 {
        return DVec3::new(0.0, 0.0, p.z.signum());
    }
    // From the nearest point of the core circle to p.
    p - DVec3::new(p.x / rho, p.y / rho, 0.0)
}
