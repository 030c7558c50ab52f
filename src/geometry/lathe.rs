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
//!
//! The straight edges are kept in runs whose heights never turn, so that
//! the edges within the heights a line reaches near the profile are found
//! by bisection, and each vertex's side is found once for its two edges.
//! The line's distance from the axis is convex in its height, so an edge
//! whose two ends are farther from the axis than the trace is not crossed
//! and is passed over with no root found; a long stretch of a run is passed
//! over a block of edges at a time where the trace stays clear of the
//! block's box.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::math::poly::{Poly, MAX_DEGREE};
use crate::plane::{side_changes, Ctrl, Curve, Cuts, Region, SCAN_EDGES};
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
    /// The straight edges off the axis, in runs along the outlines.
    chains: Arc<[Chain]>,
    /// The boxes of each run's blocks of [`BLOCK`] edges (its last block
    /// may hold fewer).
    blocks: Arc<[(DVec2, DVec2)]>,
    /// The curved edges.
    curves: Arc<[u32]>,
}

/// The edges of a run tested as one box before any of them is.
const BLOCK: usize = 8;

/// A run of straight edges, each starting where the one before it ends,
/// whose heights never turn: edges `first..first + len`, their heights
/// rising (never falling) along the run, or falling (never rising). The
/// edges a height range meets are then a contiguous part of the run, found
/// by bisection, and each vertex is shared by the two edges that meet at
/// it, so its side of the line's trace is found once.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Chain {
    first: u32,
    len: u32,
    rising: bool,
    /// Its first block's index in [`Lathe::blocks`].
    block: u32,
}

/// The runs of [`Chain`] in the straight edges of `edges` that `keep`
/// holds, and the other edges `keep` holds (the curved ones).
fn chains_of(
    edges: &[(DVec2, DVec2)],
    ctrl: &[Ctrl],
    keep: impl Fn(usize) -> bool,
) -> (Vec<Chain>, Vec<u32>) {
    let (mut chains, mut curves) = (Vec::<Chain>::new(), Vec::new());
    // The run being grown, and its direction once an edge is not level.
    let mut dir: Option<bool> = None;
    for (k, &(a, b)) in edges.iter().enumerate() {
        if !keep(k) {
            continue;
        }
        if ctrl[k] != Ctrl::Line {
            curves.push(k as u32);
            continue;
        }
        let step = (b.y != a.y).then_some(b.y > a.y);
        let joins = chains.last().is_some_and(|c| {
            let last = (c.first + c.len) as usize;
            last == k && edges[k - 1].1 == a && (step.is_none() || dir.is_none() || step == dir)
        });
        match chains.last_mut() {
            Some(c) if joins => {
                c.len += 1;
                dir = dir.or(step);
                c.rising = dir.unwrap_or(true);
            }
            _ => {
                dir = step;
                chains.push(Chain {
                    first: k as u32,
                    len: 1,
                    rising: dir.unwrap_or(true),
                    block: 0,
                });
            }
        }
    }
    (chains, curves)
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
            .collect::<Arc<[(DVec2, DVec2)]>>();
        let on_axis = |k: usize| boxes[k].0.x > boxes[k].1.x;
        let (mut chains, curves) = chains_of(&profile.edges, &profile.ctrl, |k| !on_axis(k));
        let mut blocks = Vec::new();
        for ch in &mut chains {
            ch.block = blocks.len() as u32;
            let run = &boxes[ch.first as usize..(ch.first + ch.len) as usize];
            blocks.extend(run.chunks(BLOCK).map(|b| {
                b.iter()
                    .fold(b[0], |(lo, hi), &(l, h)| (lo.min(l), hi.max(h)))
            }));
        }
        Lathe {
            profile,
            boxes,
            chains: chains.into(),
            blocks: blocks.into(),
            curves: curves.into(),
        }
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
            LatheRoots::Two(t0, t1) => {
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
        // Straight edge k, its ends' sides of the trace `ga` and `gb`.
        let mut line = |k: usize, ga: bool, gb: bool| {
            let (a, b) = self.profile.edges[k];
            let (lo, hi) = self.boxes[k];
            // An edge whose ends lie on two sides of the trace is crossed
            // (within the heights it reaches and as near as its ends): the
            // test is for the others.
            if ga == gb && !meets(lo, hi) {
                return;
            }
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
                LatheRoots::One(w / nzd)
            } else {
                roots(alpha, beta, gamma)
            };
            let (t0, t1, count) = match r {
                LatheRoots::None => (0.0, 0.0, 0),
                LatheRoots::One(t) => (t, t, 1),
                LatheRoots::Two(t0, t1) => (t0, t1, 2),
            };
            let fix = |t: f64| if n.x == 0.0 { t } else { polish(t) };
            if ga != gb {
                // One crossing: the root nearest the edge.
                let off = |l: f64| (l - l.clamp(0.0, 1.0)).abs();
                let mut best: Option<(f64, f64)> = None;
                for t in [t0, t1].into_iter().take(count) {
                    if let Some(l) = on_edge(t) {
                        if best.map_or(true, |(_, b)| off(l) < b) {
                            best = Some((t, off(l)));
                        }
                    }
                }
                if let Some((t, _)) = best {
                    cuts.push((fix(t), k as u32));
                }
            } else if count == 2 {
                let mut found = [(0.0, 0.0); 2];
                let mut m = 0;
                for t in [fix(t0), fix(t1)] {
                    if let Some(l) = on_edge(t) {
                        found[m] = (t, l);
                        m += 1;
                    }
                }
                if m == 2 && found.iter().all(|&(_, l)| l > 0.0 && l < 1.0) {
                    // Both ends on one side: the edge dips across the curve.
                    cuts.push((found[0].0, k as u32));
                    cuts.push((found[1].0, k as u32));
                }
            }
        };
        // The straight edges, run by run: those within the heights the line
        // reaches near the profile (as `meets` first asks) are a contiguous
        // part of each run.
        let (z0, z1) = (z_lo - pad, z_hi + pad);
        for ch in self.chains.iter() {
            let first = ch.first as usize;
            let run = &self.profile.edges[first..first + ch.len as usize];
            let (s, e) = if ch.rising {
                (
                    run.partition_point(|&(_, b)| b.y < z0),
                    run.partition_point(|&(a, _)| a.y <= z1),
                )
            } else {
                (
                    run.partition_point(|&(_, b)| b.y > z1),
                    run.partition_point(|&(a, _)| a.y >= z0),
                )
            };
            if s >= e {
                continue;
            }
            // Both ends of an edge farther from the axis than the trace: the
            // distance from the axis along the line is convex in the height
            // (a norm of an affine map of it) and along the edge affine, so
            // the trace stays nearer than the edge between them, and the
            // edge is not crossed. Each vertex's side is found once. More
            // than two blocks of edges are looked at block by block: a
            // block's box the trace passes clear of (farther from the axis
            // than all of it, or nearer at both ends of its heights and so
            // between them) holds no edge crossed.
            let by_block = e - s > 2 * BLOCK;
            let mut ga = None;
            for j in s / BLOCK..e.div_ceil(BLOCK) {
                let (lo, hi) = self.blocks[ch.block as usize + j];
                if by_block && apart_radially(lo, hi) {
                    ga = None;
                    continue;
                }
                for (i, &(a, b)) in run
                    .iter()
                    .enumerate()
                    .take(e.min((j + 1) * BLOCK))
                    .skip(s.max(j * BLOCK))
                {
                    let (sa, sb) = (ga.unwrap_or_else(|| side(a)), side(b));
                    if !(sa && sb) {
                        line(first + i, sa, sb);
                    }
                    ga = Some(sb);
                }
            }
        }
        // Curved edge k.
        let mut curve = |k: usize| {
            let (a, b) = self.profile.edges[k];
            let ctrl = self.profile.ctrl[k];
            let (lo, hi) = self.boxes[k];
            if !meets(lo, hi) {
                return;
            }
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
                    if let LatheRoots::Two(t0, t1) = roots(a2, b2, c2 - q.x * q.x) {
                        let off = |t: f64| (o.z + t * d.z - q.y).abs();
                        t = if off(t0) <= off(t1) { t0 } else { t1 };
                    }
                }
                cuts.push((t, k as u32));
            });
        };
        // The curves: those of a large profile through its tree, whose
        // boxes hold their edges' boxes (a box the line's trace misses
        // holds no edge it meets).
        match &self.profile.tree {
            Some(tree) if self.curves.len() > SCAN_EDGES => tree.visit_boxes(meets, &mut |k| {
                if self.profile.ctrl[k as usize] != Ctrl::Line {
                    curve(k as usize)
                }
            }),
            _ => self.curves.iter().for_each(|&k| curve(k as usize)),
        }
    }
}

enum LatheRoots {
    None,
    One(f64),
    Two(f64, f64),
}

/// The real roots of α x² + β x + γ, sorted, by the stable formula.
fn roots(alpha: f64, beta: f64, gamma: f64) -> LatheRoots {
    if alpha == 0.0 {
        return if beta == 0.0 {
            LatheRoots::None
        } else {
            LatheRoots::One(-gamma / beta)
        };
    }
    let disc = beta * beta - 4.0 * alpha * gamma;
    if disc < 0.0 {
        return LatheRoots::None;
    }
    let q = -0.5 * (beta + beta.signum() * disc.sqrt());
    if q == 0.0 {
        return LatheRoots::Two(0.0, 0.0);
    }
    let (x, y) = (q / alpha, gamma / q);
    LatheRoots::Two(x.min(y), x.max(y))
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
    /// profile's farthest point along (|d_xy|, d_z), turned to d's azimuth
    /// (to +x when d is along the axis: a point of the solid, not of the
    /// axis, which [`crate::csg::Csg::extreme`] then tests against what is
    /// cut away).
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let flat = d.truncate();
        let u = flat.try_normalize().unwrap_or(DVec2::X);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::solid::Need;
    use crate::plane::tests::uniform;
    use crate::plane::Outlines;
    use crate::stats::Stats;

    /// A profile of `n` wall vertices between the axis's ends: their
    /// heights mostly rising, some level (repeated) and some falling, so
    /// that the walls split into several runs, with a hole; with `curves`
    /// of 1 in `curves` wall edges bowed (a quadratic through a control
    /// point off its middle), 0 for none.
    fn profile(rnd: &mut impl FnMut() -> f64, n: usize, curves: usize) -> Region {
        let mut wall = vec![DVec2::new(0.0, 0.0)];
        let mut z = 0.0;
        for i in 0..n {
            let r = 1.0 + 3.0 * rnd();
            let step = rnd();
            z += if step < 0.15 {
                0.0
            } else if step < 0.3 {
                -0.2 * rnd()
            } else {
                0.5 * rnd()
            };
            // Now and then a vertex repeated at the same height.
            if i % 7 == 3 {
                wall.push(DVec2::new(r, z));
            }
            wall.push(DVec2::new(r, z));
        }
        wall.dedup();
        wall.push(DVec2::new(0.0, z.max(0.0) + 0.5));
        let hole = (0..5)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 5.0;
                DVec2::new(0.7 + 0.3 * a.cos(), z * 0.5 + 0.3 * a.sin())
            })
            .collect();
        let bows = (0..wall.len())
            .map(|i| {
                let (a, b) = (wall[i], wall[(i + 1) % wall.len()]);
                if curves == 0 || i % curves != 0 || i + 1 == wall.len() || a.x == 0.0 {
                    return Ctrl::Line;
                }
                let bow = (b - a).perp() * (0.6 * (rnd() - 0.5));
                let c = (a + b) * 0.5 + bow;
                Ctrl::Quad(DVec2::new(c.x.max(0.1), c.y))
            })
            .collect();
        let mut outlines = Outlines::polygons(vec![wall, hole]);
        outlines.ctrl = vec![bows, vec![Ctrl::Line; 5]];
        Region::new(outlines)
    }

    /// Every span's middle is inside the profile turned and every gap's
    /// middle outside, by the profile's own inside test (which counts the
    /// edges a horizontal line crosses, not the turned trace): a crossing
    /// missed or made up flips what follows it.
    #[test]
    fn spans_agree_with_the_inside_test_on_profiles_of_many_runs() {
        let mut rnd = uniform(17);
        let (mut checked, mut many_curves) = (0, false);
        for case in 0..300 {
            // Straight, a few curves, and more curves than are checked
            // one by one (through the profile's tree).
            let curves = [0, 5, 1][case % 3];
            let region = Arc::new(profile(&mut rnd, 10 + case % 60, curves));
            let lathe = Lathe::new(region.clone());
            assert!(lathe.chains.len() > 1, "one run: {:?}", lathe.chains);
            many_curves |= lathe.curves.len() > SCAN_EDGES;
            let (lo, hi) = (region.lo, region.hi);
            for _ in 0..40 {
                let d = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
                let target = DVec3::new(
                    hi.x * 2.0 * (rnd() - 0.5),
                    hi.x * 2.0 * (rnd() - 0.5),
                    lo.y + (hi.y - lo.y) * rnd(),
                );
                let o = target - d * 20.0;
                let mut st = Stats::default();
                let mut q = Probe {
                    o,
                    d,
                    tmin: f64::NEG_INFINITY,
                    tmax: f64::INFINITY,
                    st: &mut st,
                    need: Need::Spans,
                };
                let mut spans = Vec::new();
                lathe.spans(&mut q, &mut |s| spans.push((s.0, s.2)));
                // Points along the line, each inside just where a span
                // holds it: every 0.05 across the solid and the middles of
                // the spans and gaps, but for those within rounding of a
                // span's end.
                let mut marks: Vec<f64> = (0..800).map(|i| 0.05 * i as f64).collect();
                for (i, &(t0, t1)) in spans.iter().enumerate() {
                    marks.push(0.5 * (t0 + t1));
                    if let Some(&(next, _)) = spans.get(i + 1) {
                        marks.push(0.5 * (t1 + next));
                        assert!(t1 <= next, "spans overlap: {spans:?}");
                    }
                }
                for t in marks {
                    if spans
                        .iter()
                        .any(|s| (s.0 - t).abs().min((s.1 - t).abs()) < 1e-6)
                    {
                        continue;
                    }
                    let inside = spans.iter().any(|s| s.0 < t && t < s.1);
                    assert_eq!(
                        lathe.contains(o + d * t),
                        inside,
                        "case {case}: at t = {t} along {o:?} + t {d:?}, spans {spans:?}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 1_000_000 && many_curves, "{checked}");
    }
}
