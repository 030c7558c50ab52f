//! A solid of revolution: a profile region in the (r, z) half-plane r ≥ 0
//! turned about the z axis — OpenSCAD's `rotate_extrude` of polygons, in
//! object space. It carries its profile by reference.
//!
//! A point is inside when (√(x² + y²), z) is in the profile. Along the line
//! o + t·d the distance from the axis is ρ(t) = √(A t² + B t + C), so the
//! line's trace in the half-plane is the curve r = ρ(t), z = z(t) (a
//! hyperbola's branch), and it crosses the profile's edge from a to b where
//! g(λ) = r(λ)² − ρ(t(λ))² changes sign, a quadratic in the edge's
//! parameter λ when z(t) is linear in t. Each vertex is put on one side of
//! the curve by the same test for both of its edges (g > 0 or not), so a
//! crossing at a vertex counts once and a touch counts twice or not at all,
//! as the line–edge rule of [`crate::plane`] does. The crossings, sorted in
//! t, are paired even-odd from t = −∞ (far from the axis, outside). A line
//! across the axis at constant z (d_z = 0) traces its half-line twice, in
//! and out, and a line along z traces a line of the half-plane: both are
//! read from the plane's own line spans. The side over edge k is a cone, a
//! cylinder or a disc; parts are the edges' indices.

use super::poly::{Poly, MAX_DEGREE};
use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::plane::{side_changes, Ctrl, Curve, Cuts, Region};
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// A line whose direction's vertical part is at most this fraction of its
/// horizontal part (or the other way round) is taken as level (as along
/// the axis): over the stretch near the solid, of its size over the larger
/// part, the smaller moves it 10⁻¹⁰⁰ of that size, far below any rounding,
/// while the general path's squares of t = Δz/d_z would overflow (a d_z
/// below the normal numbers made them ±∞, and the line missed the solid).
pub(super) const FLAT: f64 = 1e-100;

#[derive(Clone, Debug, PartialEq)]
pub struct Lathe {
    /// The profile: x is the distance from the axis (all x ≥ 0), y is z.
    pub profile: Arc<Region>,
    /// Each edge's box (a curve's: its control points'), empty for a
    /// straight edge on the axis, which turns into no surface: the line's
    /// trace meets r = 0 only by touching it, where the region goes on.
    boxes: Arc<[(DVec2, DVec2)]>,
}

impl Lathe {
    pub fn new(profile: Arc<Region>) -> Lathe {
        let boxes = profile
            .edges
            .iter()
            .zip(&profile.ctrl)
            .map(|(&(a, b), ctrl)| {
                if a.x == 0.0 && b.x == 0.0 && *ctrl == Ctrl::Line {
                    return (DVec2::INFINITY, DVec2::NEG_INFINITY);
                }
                ctrl.bounds(a, b)
            })
            .collect();
        Lathe { profile, boxes }
    }

    /// The crossings `(t, edge)` of the line with the profile's sides, for
    /// a line with both d_z ≠ 0 and d_xy ≠ 0.
    fn crossings(&self, o: DVec3, d: DVec3, cuts: &mut Cuts) {
        let (oxy, dxy) = (o.truncate(), d.truncate());
        let (a2, b2, c2) = (
            dxy.length_squared(),
            2.0 * oxy.dot(dxy),
            oxy.length_squared(),
        );
        let rho2 = |t: f64| (a2 * t + b2) * t + c2;
        // Which side of the curve a profile point lies on: farther from
        // the axis than the line at its height (value > 0), or not.
        let value = |v: DVec2| {
            let t = (v.y - o.z) / d.z;
            v.x * v.x - rho2(t)
        };
        let side = |v: DVec2| value(v) > 0.0;
        // Where the line is within the profile's largest radius, and so
        // the heights it can meet the profile at.
        let rmax = self.profile.hi.x.max(0.0);
        let (z_lo, z_hi) = match roots(a2, b2, c2 - rmax * rmax * (1.0 + 1e-9)) {
            Roots::Two(t0, t1) => {
                let (za, zb) = (o.z + t0 * d.z, o.z + t1 * d.z);
                (za.min(zb), za.max(zb))
            }
            _ => return,
        };
        let pad = 1e-9
            * (z_hi - z_lo)
                .abs()
                .max(self.profile.hi.y.abs().max(self.profile.lo.y.abs()));
        // Whether the line, while its height is within an edge's heights,
        // stays farther from the axis than the edge's largest radius or
        // nearer than its smallest, by more than the rounding of `value`:
        // then the edge cannot be crossed, and both its ends are on one
        // side (the same for each: `value` < 0, or > 0), as they would be
        // found. The edge (a curve: its control points' hull) lies within
        // the box [lo, hi].
        let tc = -b2 / (2.0 * a2);
        let inv_dz = 1.0 / d.z;
        let apart_radially = |lo: DVec2, hi: DVec2| {
            let (ta, tb) = ((lo.y - o.z) * inv_dz, (hi.y - o.z) * inv_dz);
            let (ta, tb) = (ta.min(tb), ta.max(tb));
            let far = ta.abs().max(tb.abs());
            let r = hi.x.max(-lo.x);
            let margin = 1e-12 * (r * r + (a2 * far + b2.abs()) * far + c2);
            // (max then min: `clamp` would panic on a NaN end, as a
            // subnormal d_z makes of a box at the origin's height.)
            let near = rho2(tc.max(ta).min(tb));
            if near - r * r > margin {
                return true;
            }
            lo.x > 0.0 && lo.x * lo.x - rho2(ta).max(rho2(tb)) > margin
        };
        let meets = |lo: DVec2, hi: DVec2| {
            hi.y >= z_lo - pad && lo.y <= z_hi + pad && !apart_radially(lo, hi)
        };
        let mut cross = |k: usize| {
            let (a, b) = self.profile.edges[k];
            let ctrl = self.profile.ctrl[k];
            let (lo, hi) = self.boxes[k];
            if !meets(lo, hi) {
                return;
            }
            if ctrl != Ctrl::Line {
                // A curve (r, z) = B(u): the line's height reaches z = Z(u)
                // at t(u) = (Z(u) − o_z)/d_z, where its squared distance
                // from the axis is ρ²(t(u)), so the curve's side of the
                // line's trace is the sign of X(u)² − ρ²(t(u)), a
                // polynomial of degree ≤ 6 (2·degree) in u.
                let c = Curve::new(a, ctrl, b, DVec2::ZERO);
                let deg = c.degree;
                let mut xs = [0.0f64; MAX_DEGREE + 1];
                let mut ts = [0.0f64; MAX_DEGREE + 1];
                for i in 0..=deg {
                    xs[i] = c.k[i].x;
                    ts[i] = c.k[i].y / d.z;
                }
                ts[0] -= o.z / d.z;
                let mul = |p: &Poly, q: &Poly| {
                    let mut r = [0.0f64; MAX_DEGREE + 1];
                    for i in 0..=deg {
                        for j in 0..=deg {
                            r[i + j] += p[i] * q[j];
                        }
                    }
                    r
                };
                let (x2, t2) = (mul(&xs, &xs), mul(&ts, &ts));
                let mut f = [0.0f64; MAX_DEGREE + 1];
                for i in 0..=MAX_DEGREE {
                    f[i] = x2[i] - (a2 * t2[i] + b2 * ts[i]);
                }
                f[0] -= c2;
                // The expanded polynomial cancels; each root is polished
                // by Newton steps on X(u)² − |o_xy + t(u)·d_xy|² itself.
                let g = |u: f64| {
                    let q = c.at(u);
                    let t = (q.y - o.z) / d.z;
                    let w = oxy + dxy * t;
                    let dq = c.tangent(u);
                    let val = q.x * q.x - w.length_squared();
                    let der = 2.0 * q.x * dq.x - 2.0 * w.dot(dxy) * dq.y / d.z;
                    (val, der)
                };
                side_changes(value(a), value(b), &f, 2 * deg, |u| {
                    let u = if u == 0.0 || u == 1.0 {
                        u
                    } else {
                        let mut u = u;
                        for _ in 0..3 {
                            let (v, dv) = g(u);
                            if dv == 0.0 {
                                break;
                            }
                            let next = (u - v / dv).clamp(0.0, 1.0);
                            if (next - u).abs() > 1e-3 {
                                break;
                            }
                            u = next;
                        }
                        u
                    };
                    let q = match u {
                        0.0 => a,
                        1.0 => b,
                        _ => c.at(u),
                    };
                    // t from the height, or, for a line nearer the
                    // horizontal, from the radius (the root at that height).
                    let mut t = (q.y - o.z) / d.z;
                    if d.z.abs() * d.z.abs() < 0.25 * a2 {
                        if let Roots::Two(t0, t1) = roots(a2, b2, c2 - q.x * q.x) {
                            let off = |t: f64| (o.z + t * d.z - q.y).abs();
                            t = if off(t0) <= off(t1) { t0 } else { t1 };
                        }
                    }
                    cuts.push((t, k as u32));
                });
                return;
            }
            let (ga, gb) = (side(a), side(b));
            // The edge's line n·(r, z) = c turned about the axis is a cone:
            // n_r ρ(t) = c − n_z z(t), squared a quadratic in t (as stable
            // as the cone's own), its roots kept where ρ ≥ 0 is the nappe.
            let e = b - a;
            let n = e.perp();
            let c = n.dot(a);
            let w = c - n.y * o.z; // c − n_z z(t) = w − n_z d_z t
            let (nr2, nzd) = (n.x * n.x, n.y * d.z);
            let alpha = nr2 * a2 - nzd * nzd;
            let beta = nr2 * b2 + 2.0 * nzd * w;
            let gamma = nr2 * c2 - w * w;
            let on_edge = |t: f64| -> Option<f64> {
                if n.x * (w - nzd * t) < 0.0 {
                    return None; // the mirror nappe, at ρ < 0
                }
                let p = DVec2::new(rho2(t).max(0.0).sqrt(), o.z + t * d.z);
                Some((p - a).dot(e) / e.length_squared())
            };
            // A flat edge (n_r = 0) is a plane z = const: one double root.
            // A cone's roots are polished by Newton steps on the unsquared
            // n_r ρ(t) − (w − n_z d_z t), whose rounding does not grow as
            // the squared form's does where the cone narrows.
            let polish = |t: f64| {
                let mut t = t;
                for _ in 0..2 {
                    let q = oxy + dxy * t;
                    let rho = q.length();
                    if rho == 0.0 {
                        break;
                    }
                    let h = n.x * rho - (w - nzd * t);
                    let dh = n.x * q.dot(dxy) / rho + nzd;
                    if dh == 0.0 {
                        break;
                    }
                    let next = t - h / dh;
                    if !(next - t).is_finite() || (next - t).abs() > 1e-6 * (t.abs() + 1.0) {
                        break;
                    }
                    t = next;
                }
                t
            };
            let r = if n.x == 0.0 {
                Roots::One(w / nzd)
            } else {
                match roots(alpha, beta, gamma) {
                    Roots::Two(t0, t1) => Roots::Two(polish(t0), polish(t1)),
                    Roots::One(t) => Roots::One(polish(t)),
                    Roots::None => Roots::None,
                }
            };
            let mut found = [(0.0, 0.0); 2];
            let mut m = 0;
            let (t0, t1, count) = match r {
                Roots::None => (0.0, 0.0, 0),
                Roots::One(t) => (t, t, 1),
                Roots::Two(t0, t1) => (t0, t1, 2),
            };
            for t in [t0, t1].into_iter().take(count) {
                if let Some(l) = on_edge(t) {
                    found[m] = (t, l);
                    m += 1;
                }
            }
            let found = &found[..m];
            if ga != gb {
                // One crossing: the root nearest the edge.
                let off = |l: f64| (l - l.clamp(0.0, 1.0)).abs();
                if let Some(&(t, _)) = found.iter().min_by(|x, y| off(x.1).total_cmp(&off(y.1))) {
                    cuts.push((t, k as u32));
                }
            } else if found.len() == 2 && found.iter().all(|&(_, l)| l > 0.0 && l < 1.0) {
                // Both ends on one side: the edge dips across the curve.
                cuts.push((found[0].0, k as u32));
                cuts.push((found[1].0, k as u32));
            }
        };
        // The tree's boxes hold their edges' boxes, and a box the line's
        // trace misses holds no edge it meets.
        match &self.profile.tree {
            Some(tree) => tree.visit_boxes(meets, &mut |k| cross(k as usize)),
            None => (0..self.profile.edges.len()).for_each(cross),
        }
    }
}

enum Roots {
    None,
    One(f64),
    Two(f64, f64),
}

/// The real roots of α x² + β x + γ, sorted, by the stable formula.
fn roots(alpha: f64, beta: f64, gamma: f64) -> Roots {
    if alpha == 0.0 {
        return if beta == 0.0 {
            Roots::None
        } else {
            Roots::One(-gamma / beta)
        };
    }
    let disc = beta * beta - 4.0 * alpha * gamma;
    if disc < 0.0 {
        return Roots::None;
    }
    let q = -0.5 * (beta + beta.signum() * disc.sqrt());
    if q == 0.0 {
        return Roots::Two(0.0, 0.0);
    }
    let (x, y) = (q / alpha, gamma / q);
    Roots::Two(x.min(y), x.max(y))
}

impl Solid for Lathe {
    const NAME: &'static str = "rotate_extrude";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let (o, d) = (q.o, q.d);
        let (oxy, dxy) = (o.truncate(), d.truncate());
        let region = &self.profile;
        if dxy.length() <= FLAT * d.z.abs() {
            // Along the axis: a line of the half-plane at r = ρ.
            let o2 = DVec2::new(oxy.length(), o.z);
            for pair in region.crossings(o2, DVec2::new(0.0, d.z)).chunks_exact(2) {
                if pair[0].0 < pair[1].0 {
                    emit((pair[0].0, pair[0].1, pair[1].0, pair[1].1));
                }
            }
            return;
        }
        if d.z.abs() <= FLAT * dxy.length() {
            // At one height: the half-line r ≥ ρ_min, traced in then out.
            let a2 = dxy.length_squared();
            let tc = -oxy.dot(dxy) / a2;
            let rmin = (oxy + tc * dxy).length();
            let reach = |r: f64| (((r - rmin) * (r + rmin)).max(0.0)).sqrt() / a2.sqrt();
            let mut out: smallvec::SmallVec<[RawSpan; 8]> = smallvec::SmallVec::new();
            let cuts = region.crossings(DVec2::new(0.0, o.z), DVec2::X);
            for pair in cuts.chunks_exact(2) {
                let ((r0, k0), (r1, k1)) = (pair[0], pair[1]);
                if r1 <= rmin || r0 >= r1 {
                    continue;
                }
                let (u0, u1) = (reach(r0.max(rmin)), reach(r1));
                if r0 <= rmin {
                    out.push((tc - u1, k1, tc + u1, k1));
                } else {
                    out.push((tc - u1, k1, tc - u0, k0));
                    out.push((tc + u0, k0, tc + u1, k1));
                }
            }
            out.sort_by(|x, y| x.0.total_cmp(&y.0));
            for s in out {
                if s.0 < s.2 {
                    emit(s);
                }
            }
            return;
        }
        let mut cuts = Cuts::new();
        self.crossings(o, d, &mut cuts);
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        for pair in cuts.chunks_exact(2) {
            if pair[0].0 < pair[1].0 {
                emit((pair[0].0, pair[0].1, pair[1].0, pair[1].1));
            }
        }
    }

    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        let q = DVec2::new(p.truncate().length(), p.z);
        let n = self.profile.normal_at(part as usize, q);
        let r = p.truncate().length();
        if r == 0.0 {
            return DVec3::new(0.0, 0.0, n.y.signum());
        }
        (p.truncate() * (n.x / r)).extend(n.y)
    }

    fn contains(&self, p: DVec3) -> bool {
        let q = DVec2::new(p.truncate().length(), p.z);
        self.profile.contains(q)
    }

    fn object_bounds(&self) -> Aabb {
        let (lo, hi) = (self.profile.lo, self.profile.hi);
        let r = hi.x.max(0.0);
        Aabb::new(DVec3::new(-r, -r, lo.y), DVec3::new(r, r, hi.y))
    }

    /// The farthest point of the circles the profile turns on: the
    /// profile's farthest point along (|d_xy|, d_z), turned to d's azimuth.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let flat = d.truncate();
        let u = flat.try_normalize().unwrap_or(DVec2::ZERO);
        let q = self.profile.farthest(DVec2::new(flat.length(), d.z));
        Some((u * q.x).extend(q.y))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![("edges", Param::Num(self.profile.edges.len() as f64))]
    }

    /// POV-Ray's lathe turns about y: points <r, z>, mapped so that it
    /// turns about z. A lathe takes one closed outline: a profile of
    /// several is the first minus the others (its holes).
    fn pov(&self) -> String {
        let pt = |p: DVec2| format!("<{:?}, {:?}>", p.x, p.y);
        let outlines = &self.profile.outlines;
        let parts: Vec<String> = outlines
            .loops
            .iter()
            .enumerate()
            .map(|(j, l)| {
                if !outlines.curved() {
                    let pts: Vec<String> = l.iter().chain(l.first()).map(|&p| pt(p)).collect();
                    return format!(
                        "lathe {{ linear_spline {}, {} }}",
                        pts.len(),
                        pts.join(", ")
                    );
                }
                // Four points a segment (as a prism's bezier_spline).
                let mut pts = Vec::new();
                for i in 0..l.len() {
                    let (a, b) = (l[i], l[(i + 1) % l.len()]);
                    let (c1, c2) = outlines.ctrl[j][i].cubic(a, b);
                    pts.extend([pt(a), pt(c1), pt(c2), pt(b)]);
                }
                format!(
                    "lathe {{ bezier_spline {}, {} }}",
                    pts.len(),
                    pts.join(", ")
                )
            })
            .collect();
        let body = if parts.len() == 1 {
            parts[0].clone()
        } else {
            format!("difference {{ {} }}", parts.join(" "))
        };
        format!("object {{ {body} matrix <1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0>")
    }
}
