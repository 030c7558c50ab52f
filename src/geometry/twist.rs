//! A twisted, or unevenly scaled, prism: OpenSCAD's `linear_extrude` with
//! `twist` or `scale = [sx, sy]` (sx ≠ sy), in object space z ∈ [0, 1],
//! as the smooth limit of OpenSCAD's slices.
//!
//! OpenSCAD (`GeometryEvaluator.cc`, `add_slice`) puts the region's point
//! p at height z at x = S(z)·R(−θz)·p, S(z) = diag(1 + (sx − 1)z, 1 + (sy −
//! 1)z), θ the twist (clockwise seen from above). So a point x is inside
//! where p(x) = R(θz)·S(z)⁻¹·x_xy is in the region. Along the line o + t·d
//! the path p(t) is no longer straight, and the side over the edge n·p = c
//! is met where
//!
//!   G(t) = A(t)·cos φ(t) + B(t)·sin φ(t) − C(t) = 0,
//!
//! φ(t) = θ·z(t), w(t) = (σy·x, σx·y)(t), A = n·w, B = −n × w, C = c·σx·σy
//! (G is n·p − c times σx·σy > 0; A, B, C are quadratics in t). Its roots
//! are isolated with guaranteed bounds: over an interval of half-width r
//! about m, |G − G(m)| ≤ r·max|G′| and |G′ − G′(m)| ≤ r·max|G″| (the maxima
//! from the quadratics' ranges, |cos|, |sin| ≤ 1), so an interval is
//! dropped when |G(m)| > r·max|G′|, holds exactly one root when G′ keeps
//! its sign and G changes sign, and is halved otherwise (down to 2⁻⁶⁰ of
//! its piece; φ changes by at most 1 radian a piece). A root counts where
//! p(t) lies on the edge itself. A ray at constant z sees a straight path
//! and the region's own crossings.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part, NO_PART};
use crate::plane::Region;
use glam::{DMat2, DVec2, DVec3};
use std::sync::Arc;

const BOTTOM: Part = 0;
const TOP: Part = 1;
const SIDE: Part = 2;

#[derive(Clone, Debug, PartialEq)]
pub struct Twisted {
    /// Straight-edged outlines only.
    pub region: Arc<Region>,
    /// OpenSCAD's twist over the height, in radians.
    pub twist: f64,
    /// The top section's scale in x and y (≥ 0).
    pub scale: DVec2,
    /// From z = −1/2 to 1/2 rather than 0 to 1 (see [`super::Prism`]).
    pub centered: bool,
}

/// A quadratic q0 + q1·t + q2·t².
#[derive(Clone, Copy, Debug)]
struct Quad([f64; 3]);

impl Quad {
    fn at(&self, t: f64) -> f64 {
        (self.0[2] * t + self.0[1]) * t + self.0[0]
    }
    fn d(&self, t: f64) -> f64 {
        2.0 * self.0[2] * t + self.0[1]
    }
    fn dd(&self) -> f64 {
        2.0 * self.0[2]
    }
    /// The largest |q| over [l, h].
    fn max_abs(&self, l: f64, h: f64) -> f64 {
        let mut m = self.at(l).abs().max(self.at(h).abs());
        if self.0[2] != 0.0 {
            let v = -self.0[1] / (2.0 * self.0[2]);
            if v > l && v < h {
                m = m.max(self.at(v).abs());
            }
        }
        m
    }
    /// The largest |q′| over [l, h].
    fn max_abs_d(&self, l: f64, h: f64) -> f64 {
        self.d(l).abs().max(self.d(h).abs())
    }
    /// u·p + v·q.
    fn comb(p: Quad, q: Quad, u: f64, v: f64) -> Quad {
        Quad([
            u * p.0[0] + v * q.0[0],
            u * p.0[1] + v * q.0[1],
            u * p.0[2] + v * q.0[2],
        ])
    }

    fn mul_lin(a: [f64; 2], b: [f64; 2]) -> Quad {
        Quad([a[0] * b[0], a[0] * b[1] + a[1] * b[0], a[1] * b[1]])
    }
}

/// G(t) = A cos φ + B sin φ − C along one side, φ = φ0 + φ1·t.
struct SideFn {
    a: Quad,
    b: Quad,
    c: Quad,
    phi: [f64; 2],
}

impl SideFn {
    fn g(&self, t: f64) -> f64 {
        let (s, c) = (self.phi[0] + self.phi[1] * t).sin_cos();
        self.a.at(t) * c + self.b.at(t) * s - self.c.at(t)
    }
    fn g1(&self, t: f64) -> f64 {
        let (s, c) = (self.phi[0] + self.phi[1] * t).sin_cos();
        let w = self.phi[1];
        self.a.d(t) * c + self.b.d(t) * s + w * (self.b.at(t) * c - self.a.at(t) * s) - self.c.d(t)
    }
    /// Bounds of |G′| and |G″| over [l, h].
    fn bounds(&self, l: f64, h: f64) -> (f64, f64) {
        let w = self.phi[1].abs();
        let (a0, b0) = (self.a.max_abs(l, h), self.b.max_abs(l, h));
        let (a1, b1) = (self.a.max_abs_d(l, h), self.b.max_abs_d(l, h));
        let (a2, b2) = (self.a.dd().abs(), self.b.dd().abs());
        let m1 = a1 + b1 + w * (a0 + b0) + self.c.max_abs_d(l, h);
        let m2 = a2 + b2 + 2.0 * w * (a1 + b1) + w * w * (a0 + b0) + self.c.dd().abs();
        // Room for the rounding of G's own evaluation.
        let slack = 1e-13 * (a0 + b0 + self.c.max_abs(l, h));
        (m1 * (1.0 + 1e-12) + slack, m2 * (1.0 + 1e-12) + slack)
    }

    /// The roots of G in [l, h) where it changes sign, appended to `out`.
    fn roots(&self, l: f64, h: f64, out: &mut smallvec::SmallVec<[f64; 8]>) {
        let (gl, gh) = (self.g(l), self.g(h));
        self.isolate(l, h, gl, gh, 0, out);
    }

    fn isolate(
        &self,
        l: f64,
        h: f64,
        gl: f64,
        gh: f64,
        depth: u32,
        out: &mut smallvec::SmallVec<[f64; 8]>,
    ) {
        let (m, r) = (0.5 * (l + h), 0.5 * (h - l));
        let gm = self.g(m);
        let (m1, m2) = self.bounds(l, h);
        let slack = 1e-13 * (self.a.max_abs(l, h) + self.b.max_abs(l, h) + self.c.max_abs(l, h));
        if gm.abs() > r * m1 + slack && (gl > 0.0) == (gm > 0.0) && (gh > 0.0) == (gm > 0.0) {
            return;
        }
        let changes = (gl > 0.0) != (gh > 0.0);
        if self.g1(m).abs() > r * m2 || depth >= 60 || m <= l || m >= h {
            // Monotone (or as narrow as it gets): one root if G changes sign.
            if changes {
                out.push(self.bisect(l, h, gl));
            }
            return;
        }
        self.isolate(l, m, gl, gm, depth + 1, out);
        self.isolate(m, h, gm, gh, depth + 1, out);
    }

    /// The sign change of G in [l, h], to the last bit.
    fn bisect(&self, mut l: f64, mut h: f64, gl: f64) -> f64 {
        let left = gl > 0.0;
        for _ in 0..200 {
            let m = 0.5 * (l + h);
            if m <= l || m >= h {
                break;
            }
            if (self.g(m) > 0.0) == left {
                l = m;
            } else {
                h = m;
            }
        }
        0.5 * (l + h)
    }
}

/// The distance from the origin to the segment a–b.
fn segment_distance(a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let u = if e == DVec2::ZERO {
        0.0
    } else {
        (-a.dot(e) / e.length_squared()).clamp(0.0, 1.0)
    };
    (a + e * u).length()
}

type Spans = smallvec::SmallVec<[(f64, f64); 2]>;

/// Where q ≤ 0 in [l, h], as at most two intervals, each widened by a
/// little (1e-9 of the range, and the roots' own rounding) so that no
/// point where q = 0 is lost.
fn nonpositive(q: Quad, l: f64, h: f64) -> Spans {
    let mut out = Spans::new();
    let pad = 1e-9 * (h - l).abs().max(l.abs().max(h.abs()) * 1e-7);
    let [c0, c1, c2] = q.0;
    let mut cuts: smallvec::SmallVec<[f64; 2]> = smallvec::SmallVec::new();
    if c2 != 0.0 {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc > 0.0 {
            let k = -0.5 * (c1 + disc.sqrt().copysign(c1));
            let (x0, x1) = (k / c2, if k != 0.0 { c0 / k } else { -c1 / (2.0 * c2) });
            cuts.push(x0.min(x1));
            cuts.push(x0.max(x1));
        }
    } else if c1 != 0.0 {
        cuts.push(-c0 / c1);
    }
    // The sign between consecutive cuts, tested at the middles.
    let mut edges: smallvec::SmallVec<[f64; 4]> = smallvec::SmallVec::new();
    edges.push(l);
    edges.extend(cuts.iter().copied().filter(|&x| x > l && x < h));
    edges.push(h);
    for w in edges.windows(2) {
        let (a, b) = (w[0], w[1]);
        if q.at(0.5 * (a + b)) <= 0.0 {
            let (a, b) = ((a - pad).max(l), (b + pad).min(h));
            match out.last_mut() {
                Some(last) if last.1 >= a => last.1 = b,
                _ => out.push((a, b)),
            }
        }
    }
    // A tangent (double root) or a root the middles missed: keep a sliver.
    for &x in &cuts {
        if x >= l && x <= h && !out.iter().any(|&(a, b)| a <= x && x <= b) {
            out.push(((x - pad).max(l), (x + pad).min(h)));
        }
    }
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out
}

/// The union of two sorted interval lists, merged.
fn union2(a: Spans, b: Spans) -> Spans {
    let mut all: smallvec::SmallVec<[(f64, f64); 4]> = a.into_iter().chain(b).collect();
    all.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out = Spans::new();
    for (l, h) in all {
        match out.last_mut() {
            Some(last) if last.1 >= l => last.1 = last.1.max(h),
            _ => out.push((l, h)),
        }
    }
    out
}

impl Twisted {
    /// The bottom's height.
    fn z_lo(&self) -> f64 {
        super::cone::bottom(self.centered)
    }

    fn sigma(&self, z: f64) -> DVec2 {
        DVec2::ONE + (self.scale - DVec2::ONE) * z
    }

    /// The region frame at height z: p = R(θz)·S(z)⁻¹·x; `None` where the
    /// section has shrunk to nothing.
    fn frame(&self, z: f64) -> Option<DMat2> {
        let s = self.sigma(z);
        (s.x > 0.0 && s.y > 0.0)
            .then(|| DMat2::from_angle(self.twist * z) * DMat2::from_diagonal(DVec2::ONE / s))
    }

    /// The sides crossed along o + t·d, t in [t0, t1] (d.z ≠ 0), as (t, part).
    fn crossings(
        &self,
        o: DVec3,
        d: DVec3,
        t0: f64,
        t1: f64,
    ) -> smallvec::SmallVec<[(f64, Part); 16]> {
        let mut cuts = smallvec::SmallVec::new();
        let k = self.scale - DVec2::ONE;
        // σ(t) = σ0 + σ1·t, x(t) = o + d·t.
        let sx = [1.0 + k.x * o.z, k.x * d.z];
        let sy = [1.0 + k.y * o.z, k.y * d.z];
        let wx = Quad::mul_lin(sy, [o.x, d.x]);
        let wy = Quad::mul_lin(sx, [o.y, d.y]);
        let ss = Quad::mul_lin(sx, sy);
        let phi = [self.twist * o.z, self.twist * d.z];
        // r(t)² = |x_xy(t)|², and σ² in x and y, to keep each edge's search
        // to where the path can reach it (below).
        let r2 = Quad([
            o.truncate().length_squared(),
            2.0 * o.truncate().dot(d.truncate()),
            d.truncate().length_squared(),
        ]);
        let (sx2, sy2) = (Quad::mul_lin(sx, sx), Quad::mul_lin(sy, sy));
        let mut roots: smallvec::SmallVec<[f64; 8]> = smallvec::SmallVec::new();
        for (e, &(a, b)) in self.region.edges.iter().enumerate() {
            let n = self.region.normals[e];
            let c = n.dot(a);
            let comb = Quad::comb;
            let side = SideFn {
                a: comb(wx, wy, n.x, n.y),
                b: comb(wx, wy, n.y, -n.x),
                c: Quad(ss.0.map(|x| c * x)),
                phi,
            };
            // The edge lies between distances ρ₀ and ρ₁ of the axis, so
            // the path meets it only where ρ₀·min σ ≤ r(t) ≤ ρ₁·max σ:
            // where r² − ρ₁²σ² ≤ 0 for σx or σy, and ρ₀²σ² − r² ≤ 0 for
            // σx or σy (quadratic inequalities, widened for rounding).
            let (rho1, rho0) = (a.length().max(b.length()), segment_distance(a, b));
            let near = |k: f64, q: Quad| comb(r2, q, 1.0, -k);
            let far = |k: f64, q: Quad| comb(q, r2, k, -1.0);
            let upper = union2(
                nonpositive(near(rho1 * rho1, sx2), t0, t1),
                nonpositive(near(rho1 * rho1, sy2), t0, t1),
            );
            let lower = union2(
                nonpositive(far(rho0 * rho0, sx2), t0, t1),
                nonpositive(far(rho0 * rho0, sy2), t0, t1),
            );
            roots.clear();
            for &(ul, uh) in &upper {
                for &(ll, lh) in &lower {
                    let (l0, h0) = (ul.max(ll), uh.min(lh));
                    if l0 > h0 {
                        continue;
                    }
                    // Pieces over which φ turns by at most a radian.
                    let pieces = ((phi[1] * (h0 - l0)).abs().ceil() as usize).clamp(1, 1 << 16);
                    for i in 0..pieces {
                        let l = l0 + (h0 - l0) * (i as f64 / pieces as f64);
                        let h = if i + 1 == pieces {
                            h0
                        } else {
                            l0 + (h0 - l0) * ((i + 1) as f64 / pieces as f64)
                        };
                        side.roots(l, h, &mut roots);
                    }
                }
            }
            roots.sort_by(f64::total_cmp);
            roots.dedup();
            let (ed, len2) = (b - a, (b - a).length_squared());
            for &t in &roots {
                let x = o + d * t;
                let Some(f) = self.frame(x.z) else { continue };
                let u = (f * x.truncate() - a).dot(ed) / len2;
                if (0.0..1.0).contains(&u) {
                    cuts.push((t, SIDE + e as Part));
                }
            }
        }
        cuts.sort_by(|x: &(f64, Part), y: &(f64, Part)| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        cuts
    }
}

impl Solid for Twisted {
    const NAME: &'static str = "linear_extrude";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        // Heights from the bottom.
        let (o, d) = (q.o - DVec3::Z * self.z_lo(), q.d);
        if d.z == 0.0 {
            // A straight path through the section at this height.
            if o.z <= 0.0 || o.z >= 1.0 {
                return;
            }
            let Some(f) = self.frame(o.z) else { return };
            let (o2, d2) = (f * o.truncate(), f * d.truncate());
            if d2 == DVec2::ZERO {
                if self.region.contains(o2) {
                    emit((f64::NEG_INFINITY, NO_PART, f64::INFINITY, NO_PART));
                }
                return;
            }
            for pair in self.region.crossings(o2, d2).chunks_exact(2) {
                let ((s0, e0), (s1, e1)) = (pair[0], pair[1]);
                if s0 < s1 {
                    emit((s0, SIDE + e0, s1, SIDE + e1));
                }
            }
            return;
        }
        let (tb, tt) = (-o.z / d.z, (1.0 - o.z) / d.z);
        let ((t0, p0), (t1, p1)) = if tb < tt {
            ((tb, BOTTOM), (tt, TOP))
        } else {
            ((tt, TOP), (tb, BOTTOM))
        };
        let cuts = self.crossings(o, d, t0, t1);
        let at = |t: f64, z: f64| {
            let x = o + d * t;
            self.frame(z)
                .is_some_and(|f| self.region.contains(f * x.truncate()))
        };
        let mut inside = at(t0, if p0 == BOTTOM { 0.0 } else { 1.0 });
        let mut start = (t0, p0);
        for &(t, part) in &cuts {
            if inside {
                if start.0 < t {
                    emit((start.0, start.1, t, part));
                }
            } else {
                start = (t, part);
            }
            inside = !inside;
        }
        if inside && start.0 < t1 {
            emit((start.0, start.1, t1, p1));
        }
    }

    /// The gradient of n·p(x) − c: S⁻¹R(θz)ᵀn in x and y, and in z
    /// n·(θ·R′(θz)S⁻¹x + R(θz)·d(S⁻¹)/dz·x).
    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        let p = p - DVec3::Z * self.z_lo();
        match part {
            BOTTOM => DVec3::NEG_Z,
            TOP => DVec3::Z,
            k => {
                let n = self.region.normals[(k - SIDE) as usize];
                let s = self.sigma(p.z).max(DVec2::splat(1e-300));
                let rot = DMat2::from_angle(self.twist * p.z);
                let inv = DVec2::ONE / s;
                let xy = rot.transpose() * n * inv;
                let x = p.truncate();
                let turn = DMat2::from_angle(self.twist * p.z + std::f64::consts::FRAC_PI_2);
                let ds = -(self.scale - DVec2::ONE) * inv * inv;
                let dz = n.dot(turn * (x * inv) * self.twist + rot * (x * ds));
                xy.extend(dz)
            }
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        let p = p - DVec3::Z * self.z_lo();
        (0.0..=1.0).contains(&p.z)
            && self
                .frame(p.z)
                .is_some_and(|f| self.region.contains(f * p.truncate()))
    }

    /// Without twist, the region's box and that box scaled at the top;
    /// with it, the disc of the farthest vertex, scaled by the larger of 1
    /// and the top scale in each direction.
    fn object_bounds(&self) -> Aabb {
        let r = &self.region;
        let grow = DVec2::ONE.max(self.scale);
        let (lo, hi) = if self.twist == 0.0 {
            (r.lo.min(r.lo * self.scale), r.hi.max(r.hi * self.scale))
        } else {
            let rho = r.edges.iter().map(|(a, _)| a.length()).fold(0.0, f64::max);
            (-grow * rho, grow * rho)
        };
        let z = self.z_lo();
        Aabb::new(lo.extend(z), hi.extend(z + 1.0))
    }

    /// Not computed: a twisted side's farthest point is not at a vertex.
    fn support(&self, _d: DVec3) -> Option<DVec3> {
        None
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("edges", Param::Num(self.region.edges.len() as f64)),
            ("twist", Param::Num(self.twist.to_degrees())),
            ("scale_x", Param::Num(self.scale.x)),
            ("scale_y", Param::Num(self.scale.y)),
            ("center", Param::Bool(self.centered)),
        ]
    }

    /// POV-Ray has no twisted prism: the export stops POV-Ray with the
    /// reason rather than draw something else.
    fn pov(&self) -> String {
        "#error \"csgrt: a twisted or unevenly scaled linear_extrude has no POV-Ray equivalent\"\nsphere { <0, 0, 0>, 0".to_string()
    }
}
