//! The turn about the z axis of any ellipse wholly at x > 0: OpenSCAD's
//! `rotate_extrude` of a rotated, scaled circle (a slanted ellipse), which
//! no linear map of a torus makes. In the half-plane of the axis and a
//! point (ρ = √(x² + y²), z) the ellipse is centred on (1, 0) — the solid
//! is placed by its transform — and is (1, 0) + M·u, |u| ≤ 1, the inside
//! of wᵀQw ≤ 1 with w = (ρ − 1, z) and Q = (MMᵀ)⁻¹.
//!
//! Along a line, ρ² and z are polynomials in its parameter, but ρ is not:
//! the boundary P + ρL = 0 (P = qa ρ² + qa − 2qb z + qc z² − 1 and L =
//! 2(qb z − qa), both polynomials) is squared into the quartic P² − ρ²L² = 0,
//! which also holds the mirror ellipse's points (ρ → −ρ). Its roots are
//! isolated as the torus's are ([`crate::math::poly::roots_in_from`]), and
//! each interval between them is classified by the exact test at its
//! middle, so a root of the mirror image changes nothing.

use super::solid::{spans_between_roots, Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::math::poly::{poly, quartic_estimates, roots_in_from, Poly, MAX_DEGREE};
use glam::{DMat2, DVec2, DVec3};

/// A turned ellipse: `m` maps the unit disc onto it, about (ρ, z) = (1, 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ring {
    pub m: DMat2,
}

impl Ring {
    /// The ellipse (1, 0) + m·u, |u| ≤ 1, turned; `None` unless it lies
    /// wholly at ρ > 0 and has an area.
    pub fn new(m: DMat2) -> Option<Ring> {
        let reach = m.row(0).length();
        (m.determinant() != 0.0 && reach < 1.0).then_some(Ring { m })
    }

    /// Q = (MMᵀ)⁻¹ as (qa, qb, qc).
    fn q(&self) -> (f64, f64, f64) {
        let q = (self.m * self.m.transpose()).inverse();
        if crate::mutant::active("ring_unslanted") {
            return (q.x_axis.x, 0.0, q.y_axis.y);
        }
        (q.x_axis.x, q.y_axis.x, q.y_axis.y)
    }

    /// wᵀQw − 1 at a point of the half-plane, for Q = [`Ring::q`]: negative
    /// inside.
    fn level((qa, qb, qc): (f64, f64, f64), rho: f64, z: f64) -> f64 {
        let w = rho - 1.0;
        qa * w * w + 2.0 * qb * w * z + qc * z * z - 1.0
    }

    /// The half-extents of the ellipse along ρ and z.
    fn reach(&self) -> DVec2 {
        DVec2::new(self.m.row(0).length(), self.m.row(1).length())
    }
}

/// a·b for polynomials of degree ≤ 2 (coefficients from the constant).
fn mul2(a: [f64; 3], b: [f64; 3]) -> [f64; 5] {
    let mut out = [0.0; 5];
    for i in 0..3 {
        for j in 0..3 {
            out[i + j] += a[i] * b[j];
        }
    }
    out
}

impl Solid for Ring {
    const NAME: &'static str = "ring";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let (o, d) = (q.o, q.d);
        let b = self.object_bounds();
        // The line clipped to the box, from its entry with a unit direction.
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for i in 0..3 {
            if d[i] == 0.0 {
                if o[i] < b.min[i] || o[i] > b.max[i] {
                    return;
                }
            } else {
                let (s, t) = ((b.min[i] - o[i]) / d[i], (b.max[i] - o[i]) / d[i]);
                lo = lo.max(s.min(t));
                hi = hi.min(s.max(t));
            }
        }
        if lo >= hi || lo.is_nan() || hi.is_nan() {
            return;
        }
        let len = d.length();
        let u = d / len;
        let p = o + lo * d;
        let span = (hi - lo) * len;
        let (qa, qb, qc) = self.q();
        // ρ²(s), z(s), P(s), L(s), from the constant term.
        let rho2 = [
            p.x * p.x + p.y * p.y,
            2.0 * (p.x * u.x + p.y * u.y),
            u.x * u.x + u.y * u.y,
        ];
        let (z0, zu) = (p.z, u.z);
        let pp = [
            qa * rho2[0] + qa - 2.0 * qb * z0 + qc * z0 * z0 - 1.0,
            qa * rho2[1] - 2.0 * qb * zu + 2.0 * qc * z0 * zu,
            qa * rho2[2] + qc * zu * zu,
        ];
        let l = [2.0 * (qb * z0 - qa), 2.0 * qb * zu, 0.0];
        let (p2, l2) = (mul2(pp, pp), mul2(l, l));
        let l2r = mul2([l2[0], l2[1], l2[2]], rho2);
        let c: Vec<f64> = (0..5).map(|i| p2[i] - l2r[i]).collect();
        let quartic: Poly = poly(&c);
        let mut roots = [0.0; MAX_DEGREE];
        let mut starts = [0.0; 4];
        let ns = if quartic[4] != 0.0 {
            quartic_estimates(&quartic, &mut starts)
        } else {
            0
        };
        let n = roots_in_from(&quartic, 4, 0.0, span, &starts[..ns], &mut roots);
        let inside = |s: f64| {
            let r2 = rho2[0] + s * (rho2[1] + s * rho2[2]);
            Ring::level((qa, qb, qc), r2.max(0.0).sqrt(), z0 + s * zu) < 0.0
        };
        spans_between_roots(&roots[..n], (span, lo, hi, len), inside, emit);
    }

    /// The gradient of wᵀQw, carried from the half-plane to space.
    fn normal(&self, p: DVec3, _part: Part) -> DVec3 {
        let (qa, qb, qc) = self.q();
        let rho = p.truncate().length();
        let w = rho - 1.0;
        let (g_rho, g_z) = (qa * w + qb * p.z, qb * w + qc * p.z);
        if rho == 0.0 {
            return DVec3::new(0.0, 0.0, g_z.signum());
        }
        DVec3::new(g_rho * p.x / rho, g_rho * p.y / rho, g_z)
    }

    fn contains(&self, p: DVec3) -> bool {
        Ring::level(self.q(), p.truncate().length(), p.z) <= 0.0
    }

    fn object_bounds(&self) -> Aabb {
        let e = self.reach();
        let r = 1.0 + e.x;
        Aabb::new(DVec3::new(-r, -r, -e.y), DVec3::new(r, r, e.y))
    }

    /// Of its hull: the point of the ellipse farthest along (|d_xy|, d_z)
    /// in the half-plane that faces d.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let flat = d.truncate();
        let (toward, across) = if flat == DVec2::ZERO {
            (DVec2::X, 0.0)
        } else {
            (flat.normalize(), flat.length())
        };
        let v = DVec2::new(across, d.z);
        let mt = self.m.transpose() * v;
        let e = if mt == DVec2::ZERO {
            DVec2::ZERO
        } else {
            self.m * (mt / mt.length())
        };
        let rho = 1.0 + e.x;
        Some((toward * rho).extend(e.y))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        let [a, b, c, d] = self.m.to_cols_array();
        vec![
            ("m00", Param::Num(a)),
            ("m10", Param::Num(b)),
            ("m01", Param::Num(c)),
            ("m11", Param::Num(d)),
        ]
    }

    /// POV-Ray's `lathe` has no ellipse: its points of the outline, every
    /// degree (a picture for comparison, not the exact solid).
    fn pov(&self) -> String {
        let mut pts: Vec<String> = (0..360)
            .map(|i| {
                let a = (i as f64).to_radians();
                let p = DVec2::new(1.0, 0.0) + self.m * DVec2::new(a.cos(), a.sin());
                format!("<{:?}, {:?}>", p.x, p.y)
            })
            .collect();
        // Closed by its first point again, to the digit.
        pts.push(pts[0].clone());
        format!(
            "object {{ lathe {{ linear_spline 361, {} }} matrix <1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0>",
            pts.join(", ")
        )
    }
}
