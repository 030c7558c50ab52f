//! A twisted, or unevenly scaled, prism: OpenSCAD's `linear_extrude` with
//! `twist` or `scale = [sx, sy]` (sx ≠ sy), in object space z ∈ [0, 1],
//! as the smooth limit of OpenSCAD's slices, over a straight-edged region
//! or an ellipse (a circle anywhere in the plane, a drawing's arc).
//!
//! OpenSCAD (`GeometryEvaluator.cc`, `add_slice`) puts the section's point
//! p at height z at x = S(z)·R(−θz)·p, S(z) = diag(1 + (sx − 1)z, 1 + (sy −
//! 1)z), θ the twist (clockwise seen from above). So a point x is inside
//! where p(x) = R(θz)·S(z)⁻¹·x_xy is in the section. Along the line o + t·d
//! the path p(t) is no longer straight. With w(t) = (σy·x, σx·y)(t) and
//! σ̄ = σx·σy (p = R(φ)·w/σ̄, φ(t) = θ·z(t)), the side over the edge n·p = c
//! is met where
//!
//!   G(t) = A(t)·cos φ + B(t)·sin φ − C(t) = 0,
//!
//! A = n·w, B = −n × w, C = c·σ̄ (G is n·p − c times σ̄ > 0; A, B, C are
//! quadratics in t). The ellipse (p − c)ᵀQ(p − c) ≤ 1 is met where σ̄² times
//! that form minus 1 vanishes: with Q = s·I + [[a, b], [b, −a]] and
//! g = Q·c, it is
//!
//!   s|w|² + σ̄²(cᵀQc − 1) − 2σ̄[(w·g) cos φ + (w × g) sin φ]
//!     + [a(wx² − wy²) + 2b·wx·wy] cos 2φ + [b(wx² − wy²) − 2a·wx·wy] sin 2φ,
//!
//! quartics in t (quadratics under an even scale, where w = x and σ̄ = σ
//! serve, the common factor σ² left out), the second harmonic only for an
//! ellipse that is not a circle. Roots are isolated by [`crate::math::trig`]
//! over pieces in which φ turns by at most a radian, searched only where
//! the path's distance from the axis can reach the edge or ellipse. A root
//! on an edge's line counts where p(t) lies on the edge itself. A ray at
//! constant z sees a straight path and the section's own crossings.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part, NO_PART};
use crate::math::trig::{Pol, Trig};
use crate::plane::flat::largest_stretch;
use crate::plane::{segment_distance, Region};
use glam::{DAffine2, DMat2, DVec2, DVec3};
use smallvec::SmallVec;
use std::sync::Arc;

const BOTTOM: Part = 0;
const TOP: Part = 1;
const SIDE: Part = 2;

/// What is swept.
#[derive(Clone, Debug, PartialEq)]
pub enum TwistSection {
    /// Straight-edged outlines only; edge e is part SIDE + e.
    Region(Arc<Region>),
    /// The image of the unit disc (part SIDE), not flattened.
    Ellipse(DAffine2),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Twisted {
    pub section: TwistSection,
    /// OpenSCAD's twist over the height, in radians.
    pub twist: f64,
    /// The top section's scale in x and y (≥ 0).
    pub scale: DVec2,
    /// From z = −1/2 to 1/2 rather than 0 to 1 (see [`super::Prism`]).
    pub centered: bool,
}

/// An ellipse's inside test as a quadratic form: (p − c)ᵀQ(p − c) ≤ 1.
struct Form {
    q: glam::DMat2,
    c: DVec2,
}

impl Form {
    fn of(e: &DAffine2) -> Form {
        let inv = e.matrix2.inverse();
        Form {
            q: inv.transpose() * inv,
            c: e.translation,
        }
    }

    /// ½ of the gradient of (p − c)ᵀQ(p − c).
    fn grad(&self, p: DVec2) -> DVec2 {
        self.q * (p - self.c)
    }

    fn contains(&self, p: DVec2) -> bool {
        (p - self.c).dot(self.q * (p - self.c)) <= 1.0
    }
}

impl TwistSection {
    fn contains(&self, p: DVec2) -> bool {
        match self {
            TwistSection::Region(r) => r.contains(p),
            TwistSection::Ellipse(e) => Form::of(e).contains(p),
        }
    }

    /// The farthest distance of the section from the axis (at least).
    fn reach(&self) -> f64 {
        match self {
            TwistSection::Region(r) => r.edges.iter().map(|(a, _)| a.length()).fold(0.0, f64::max),
            TwistSection::Ellipse(e) => e.translation.length() + largest_stretch(e.matrix2),
        }
    }

    /// Points whose hull holds the section: a region's corners, the
    /// corners of an ellipse's parallelogram.
    fn corners(&self) -> Vec<DVec2> {
        match self {
            TwistSection::Region(r) => r.edges.iter().map(|&(a, _)| a).collect(),
            TwistSection::Ellipse(e) => [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)]
                .map(|(u, v)| e.transform_point2(DVec2::new(u, v)))
                .to_vec(),
        }
    }

    /// The box of the section.
    fn box2(&self) -> (DVec2, DVec2) {
        match self {
            TwistSection::Region(r) => (r.lo, r.hi),
            TwistSection::Ellipse(e) => {
                let m = e.matrix2;
                let h = DVec2::new(
                    DVec2::new(m.x_axis.x, m.y_axis.x).length(),
                    DVec2::new(m.x_axis.y, m.y_axis.y).length(),
                );
                (e.translation - h, e.translation + h)
            }
        }
    }
}

/// The box of the arc v turns through by R(a·z), z from 0 to 1: its
/// ends, and its points on the axes that it passes.
fn arc_box(v: DVec2, a: f64) -> (DVec2, DVec2) {
    let r = v.length();
    if a.abs() >= std::f64::consts::TAU {
        return (DVec2::splat(-r), DVec2::splat(r));
    }
    let a0 = v.y.atan2(v.x);
    let (from, to) = (a0 + a.min(0.0), a0 + a.max(0.0));
    let end = DMat2::from_angle(a) * v;
    let (mut lo, mut hi) = (v.min(end), v.max(end));
    for k in 0..4 {
        let axis = k as f64 * std::f64::consts::FRAC_PI_2;
        // The first angle axis + 2πn at or after `from`.
        let n = ((from - axis) / std::f64::consts::TAU).ceil();
        if axis + n * std::f64::consts::TAU <= to {
            let p = [DVec2::X, DVec2::Y, DVec2::NEG_X, DVec2::NEG_Y][k] * r;
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (lo, hi)
}

type Spans = smallvec::SmallVec<[(f64, f64); 2]>;

/// Where q ≤ 0 in [l, h], as at most two intervals, each widened by a
/// little (1e-9 of the range, and the roots' own rounding) so that no
/// point where q = 0 is lost.
fn nonpositive(q: Pol, l: f64, h: f64) -> Spans {
    let mut out = Spans::new();
    let pad = 1e-9 * (h - l).abs().max(l.abs().max(h.abs()) * 1e-7);
    let [c0, c1, c2, ..] = q.c;
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

/// Where the path is both within reach of the far distance and beyond the
/// near one: the overlaps of [`TwistPath::reach`]'s two lists.
fn reach_overlaps((upper, lower): &(Spans, Spans)) -> impl Iterator<Item = (f64, f64)> + '_ {
    upper.iter().flat_map(move |&(ul, uh)| {
        lower
            .iter()
            .map(move |&(ll, lh)| (ul.max(ll), uh.min(lh)))
            .filter(|(l, h)| l <= h)
    })
}

/// The range from the first τ of [`reach_overlaps`] to the last, if any.
fn reach_range(reach: &(Spans, Spans)) -> Option<(f64, f64)> {
    reach_overlaps(reach).reduce(|(a, b), (l, h)| (a.min(l), b.max(h)))
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

    /// The box of the sections from height a to b (from the bottom, 0 ≤ a
    /// ≤ b ≤ 1): without twist, the section's box scaled by σ; with it,
    /// the box of the arcs its corners turn through (a section lies in the
    /// hull of its corners; an ellipse in its box's, a parallelogram's),
    /// scaled by σ, which lies between σ(a) and σ(b) (≥ 0) in each
    /// direction (at the ends, 1 and the top's own scale, not σ rounded).
    fn swept(&self, a: f64, b: f64) -> (DVec2, DVec2) {
        let base = if a == 0.0 { DVec2::ONE } else { self.sigma(a) };
        let top = if b == 1.0 { self.scale } else { self.sigma(b) };
        let (s0, s1) = (base.min(top), base.max(top));
        if self.twist == 0.0 {
            let (lo, hi) = self.section.box2();
            return ((lo * s0).min(lo * s1), (hi * s0).max(hi * s1));
        }
        let mut lo = DVec2::INFINITY;
        let mut hi = DVec2::NEG_INFINITY;
        for v in self.section.corners() {
            // R(−θz)·v for z in [a, b].
            let start = if a == 0.0 {
                v
            } else {
                DMat2::from_angle(-self.twist * a) * v
            };
            let (ulo, uhi) = arc_box(start, -self.twist * (b - a));
            for s in [s0, s1] {
                for u in [ulo, uhi] {
                    lo = lo.min(s * u);
                    hi = hi.max(s * u);
                }
            }
        }
        // Room for the rounding of the arcs' sines and cosines.
        let pad = DVec2::splat(1e-9 * lo.abs().max(hi.abs()).max_element());
        (lo - pad, hi + pad)
    }

    /// The section's frame at height z: p = R(θz)·S(z)⁻¹·x; `None` where
    /// the section has shrunk to nothing.
    fn frame(&self, z: f64) -> Option<DMat2> {
        let s = self.sigma(z);
        (s.x > 0.0 && s.y > 0.0)
            .then(|| DMat2::from_angle(self.twist * z) * DMat2::from_diagonal(DVec2::ONE / s))
    }

    /// The sides crossed along o + t·d, t in [t0, t1] (d.z ≠ 0), as (t, part).
    fn crossings(&self, o: DVec3, d: DVec3, t0: f64, t1: f64) -> SmallVec<[(f64, Part); 16]> {
        let mut cuts = SmallVec::new();
        let mut roots: SmallVec<[f64; 8]> = SmallVec::new();
        // The polynomials about the point of the line nearest the axis
        // within the slab: their terms are then of the section's size, not
        // of the line's length (quartics about a far origin cancel to 10⁴
        // ulps; the sides' quadratics about a camera 600 units out put its
        // hits 2·10⁻¹¹ off the surface, more than a shadow ray's start is
        // moved, and the sides shadowed themselves in specks).
        let dxy = d.truncate().length_squared();
        let near = if dxy > 0.0 {
            -o.truncate().dot(d.truncate()) / dxy
        } else {
            0.5 * (t0 + t1)
        };
        let path = TwistPath::new(self, o, d, t0, t1, near.clamp(t0, t1));
        match &self.section {
            TwistSection::Region(region) => {
                // The whole section's reach first: a line that passes
                // inside its nearest edge's distance or beyond its farthest
                // corner, scaled, crosses no side.
                let (lo, hi) = (region.lo, region.hi);
                let (rho0, rho1) = region.chord_range;
                let rho1 = if crate::mutant::active("twist_reach_shrunk") {
                    0.9 * rho1
                } else {
                    rho1
                };
                let Some((l, h)) = reach_range(&path.reach(rho0, rho1)) else {
                    return cuts;
                };
                // The path over that range, in pieces, near the section's
                // own disc (the box's centre and half diagonal).
                let discs = path.discs(l, h, 0.5 * (lo + hi), 0.5 * (hi - lo).length());
                if discs.kept == 0 {
                    return cuts;
                }
                let mut edge = |e: usize| {
                    let (a, b) = region.edges[e];
                    // The pieces of the path that may pass over the edge
                    // itself; none: no root on the edge's line is on it.
                    let near = discs.near(a, b);
                    if near == 0 {
                        return;
                    }
                    let may = |l: f64, h: f64| discs.may(near, l, h);
                    let n = region.normals[e];
                    let c = n.dot(a);
                    let comb = Pol::comb;
                    let side = Trig {
                        a: comb(path.wx, path.wy, n.x, n.y),
                        b: comb(path.wx, path.wy, n.y, -n.x),
                        c: Pol::quad([c * path.ss.c[0], c * path.ss.c[1], c * path.ss.c[2]]),
                        second: None,
                        phi: path.phi,
                    };
                    roots.clear();
                    let (rho0, rho1) = region.chord_reach[e];
                    path.roots(&side, &path.reach(rho0, rho1), 1.0, &may, &mut roots);
                    let (ed, len2) = (b - a, (b - a).length_squared());
                    for &t in &roots {
                        let x = o + d * t;
                        let Some(f) = self.frame(x.z) else { continue };
                        let u = (f * x.truncate() - a).dot(ed) / len2;
                        if (0.0..1.0).contains(&u) {
                            cuts.push((t, SIDE + e as Part));
                        }
                    }
                };
                match &region.tree {
                    // The edges in boxes some piece's disc meets.
                    Some(tree) => tree
                        .visit_boxes(|blo, bhi| discs.meets_box(blo, bhi), &mut |e| {
                            edge(e as usize)
                        }),
                    None => (0..region.edges.len()).for_each(edge),
                }
            }
            TwistSection::Ellipse(e) => {
                let side = path.ellipse(&Form::of(e), self.scale.x == self.scale.y);
                let rho1 = self.section.reach();
                let rho0 = (e.translation.length() - largest_stretch(e.matrix2)).max(0.0);
                let turns = if side.second.is_some() { 2.0 } else { 1.0 };
                // The pieces whose discs meet the ellipse's own disc.
                let reach = path.reach(rho0, rho1);
                let Some((l, h)) = reach_range(&reach) else {
                    return cuts;
                };
                let discs = path.discs(l, h, e.translation, largest_stretch(e.matrix2));
                let may = |l: f64, h: f64| discs.may(discs.kept, l, h);
                path.roots(&side, &reach, turns, &may, &mut roots);
                for &t in &roots {
                    if self.frame(o.z + d.z * t).is_some() {
                        cuts.push((t, SIDE));
                    }
                }
            }
        }
        cuts.sort_by(|x: &(f64, Part), y: &(f64, Part)| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        cuts
    }

    /// The point of the solid farthest along `d` (object space), found
    /// numerically: the section's own farthest point at height z (a
    /// corner, or the ellipse's point whose normal is the direction seen in
    /// the section's frame, R(θz)·S(z)·d) gives a value f(z); f is sampled
    /// at 16 heights and 8 more for each radian of twist, and each sample
    /// not below its neighbours is refined by golden-section search
    /// between them to the last bit. The solid's far point in every
    /// direction is what framing and `resize` measure (a side's farthest
    /// point is not at a corner, so the solid has no exact support: see
    /// [`Solid::support`]).
    pub fn far_point(&self, d: DVec3) -> DVec3 {
        let z0 = self.z_lo();
        let at = |z: f64| -> (f64, DVec2) {
            let s = self.sigma(z).max(DVec2::ZERO);
            let turn = if crate::mutant::active("twist_far_point_untwisted") {
                0.0
            } else {
                self.twist * z
            };
            let w = DMat2::from_angle(turn) * (s * d.truncate());
            let p = match &self.section {
                TwistSection::Region(r) => r
                    .edges
                    .iter()
                    .map(|&(a, _)| a)
                    .max_by(|a, b| w.dot(*a).total_cmp(&w.dot(*b)))
                    .unwrap_or(DVec2::ZERO),
                TwistSection::Ellipse(e) => {
                    let u = (e.matrix2.transpose() * w).normalize_or_zero();
                    e.translation + e.matrix2 * u
                }
            };
            (w.dot(p) + d.z * (z + z0), p)
        };
        let n = 16 + (8.0 * self.twist.abs()).ceil().min(4096.0) as usize;
        let samples: Vec<f64> = (0..=n).map(|k| at(k as f64 / n as f64).0).collect();
        let mut best = (f64::NEG_INFINITY, 0.0);
        for k in 0..=n {
            let below = |j: usize| samples[j] <= samples[k];
            if !((k == 0 || below(k - 1)) && (k == n || below(k + 1))) {
                continue;
            }
            let (mut l, mut h) = (
                (k.max(1) - 1) as f64 / n as f64,
                (k + 1).min(n) as f64 / n as f64,
            );
            const G: f64 = 0.618_033_988_749_894_9;
            for _ in 0..100 {
                let (a, b) = (h - G * (h - l), l + G * (h - l));
                if !(a > l && b < h && a < b) {
                    break;
                }
                if at(a).0 < at(b).0 {
                    l = a;
                } else {
                    h = b;
                }
            }
            for z in [k as f64 / n as f64, 0.5 * (l + h)] {
                let v = at(z).0;
                if v > best.0 {
                    best = (v, z);
                }
            }
        }
        let z = best.1;
        let p = at(z).1;
        let s = self.sigma(z).max(DVec2::ZERO);
        let x = DMat2::from_diagonal(s) * (DMat2::from_angle(-self.twist * z) * p);
        x.extend(z + z0)
    }

    /// The gradient's direction in the section at `p` on `part` (p in the
    /// section's own coordinates).
    fn section_normal(&self, p: DVec2, part: Part) -> DVec2 {
        match &self.section {
            TwistSection::Region(r) => r.normals[(part - SIDE) as usize],
            TwistSection::Ellipse(e) => Form::of(e).grad(p),
        }
    }
}

/// How many pieces [`TwistPath::discs`] cuts a path into.
const DISCS: usize = 8;

/// A twisted extrusion's path in its section's plane cut into pieces,
/// piece i (τ from `cuts[i]` to `cuts[i + 1]`) within `radius[i]` of
/// `centre[i]`: a root of an edge's line over a piece whose disc misses
/// the edge is not on the edge.
struct Discs {
    cuts: [f64; DISCS + 1],
    centre: [DVec2; DISCS],
    radius: [f64; DISCS],
    /// The pieces near the section, one bit each.
    kept: u32,
}

impl Discs {
    /// Whether a piece near the section has a disc that meets the box
    /// [lo, hi].
    fn meets_box(&self, lo: DVec2, hi: DVec2) -> bool {
        (0..DISCS).any(|i| {
            self.kept & (1 << i) != 0
                && (self.radius[i] == f64::INFINITY
                    || (self.centre[i].clamp(lo, hi) - self.centre[i]).length() <= self.radius[i])
        })
    }

    /// The pieces near the section whose discs meet the segment a–b, one
    /// bit each.
    fn near(&self, a: DVec2, b: DVec2) -> u32 {
        let mut bits = 0;
        for i in (0..DISCS).filter(|i| self.kept & (1 << i) != 0) {
            if self.radius[i] == f64::INFINITY
                || segment_distance(a - self.centre[i], b - self.centre[i]) <= self.radius[i]
            {
                bits |= 1 << i;
            }
        }
        bits
    }

    /// Whether [l, h] meets one of the pieces in `bits`.
    fn may(&self, bits: u32, l: f64, h: f64) -> bool {
        (0..DISCS).any(|i| bits & (1 << i) != 0 && self.cuts[i] <= h && self.cuts[i + 1] >= l)
    }
}

/// The line o + t·d in a twisted extrusion's terms (see the module
/// comment): σ, w, σ̄ and φ as polynomials in t.
struct TwistPath {
    wx: Pol,
    wy: Pol,
    /// σ̄ = σx·σy.
    ss: Pol,
    phi: [f64; 2],
    /// r(t)² = |x_xy(t)|², and σx², σy²: where the path can reach a
    /// distance from the axis.
    r2: Pol,
    sx2: Pol,
    sy2: Pol,
    /// σx and σy, and x and y, as linear functions of t.
    sx: [f64; 2],
    sy: [f64; 2],
    x: [f64; 2],
    y: [f64; 2],
    /// The range of τ, and the t where τ = 0.
    t0: f64,
    t1: f64,
    tc: f64,
}

impl TwistPath {
    /// The line o + t·d over [t0, t1], its polynomials in τ = t − tc.
    fn new(tw: &Twisted, o: DVec3, d: DVec3, t0: f64, t1: f64, tc: f64) -> TwistPath {
        let o = o + d * tc;
        let k = tw.scale - DVec2::ONE;
        // σ(τ) = σ0 + σ1·τ, x(τ) = o + d·τ.
        let sx = [1.0 + k.x * o.z, k.x * d.z];
        let sy = [1.0 + k.y * o.z, k.y * d.z];
        TwistPath {
            wx: Pol::mul_lin(sy, [o.x, d.x]),
            wy: Pol::mul_lin(sx, [o.y, d.y]),
            ss: Pol::mul_lin(sx, sy),
            phi: [tw.twist * o.z, tw.twist * d.z],
            r2: Pol::quad([
                o.truncate().length_squared(),
                2.0 * o.truncate().dot(d.truncate()),
                d.truncate().length_squared(),
            ]),
            sx2: Pol::mul_lin(sx, sx),
            sy2: Pol::mul_lin(sy, sy),
            sx,
            sy,
            x: [o.x, d.x],
            y: [o.y, d.y],
            t0: t0 - tc,
            t1: t1 - tc,
            tc,
        }
    }

    /// The ellipse's G (see the module comment); under an even scale
    /// w = x, σ̄ = σ.
    fn ellipse(&self, f: &Form, even: bool) -> Trig {
        let lin = |c: [f64; 2]| Pol {
            c: [c[0], c[1], 0.0, 0.0, 0.0],
            deg: 1,
        };
        let (wx, wy, ss) = if even {
            (lin(self.x), lin(self.y), lin(self.sx))
        } else {
            (self.wx, self.wy, self.ss)
        };
        let q = f.q;
        let (s, a, b) = (
            0.5 * (q.x_axis.x + q.y_axis.y),
            0.5 * (q.x_axis.x - q.y_axis.y),
            q.x_axis.y,
        );
        let g = q * f.c;
        let k0 = f.c.dot(g) - 1.0;
        let (xx, yy, xy) = (wx.mul(&wx), wy.mul(&wy), wx.mul(&wy));
        let norm2 = Pol::comb(xx, yy, 1.0, 1.0);
        let diff = Pol::comb(xx, yy, 1.0, -1.0);
        let ss2 = ss.mul(&ss);
        // C is minus the constant harmonic.
        let c = Pol::comb(norm2, ss2, -s, -k0);
        let dot = Pol::comb(wx, wy, g.x, g.y);
        let cross = Pol::comb(wx, wy, g.y, -g.x);
        let turn = if crate::mutant::active("ellipse_turned_back") {
            -1.0
        } else {
            1.0
        };
        let second = (a != 0.0 || b != 0.0).then(|| {
            (
                Pol::comb(diff, xy, a, 2.0 * b),
                Pol::comb(diff, xy, turn * b, turn * -2.0 * a),
            )
        });
        Trig {
            a: ss.mul(&dot).scaled(-2.0),
            b: ss.mul(&cross).scaled(-2.0),
            c,
            second,
            phi: self.phi,
        }
    }

    /// The path p(τ) = R(φ)·S⁻¹·x in the section's plane from τ = t0 to
    /// t1 cut into [`DISCS`] pieces of equal length, each within a disc
    /// (see [`Discs`]); a piece whose disc misses the disc of `centre` and
    /// `radius` (one that holds the section) is left out.
    fn discs(&self, t0: f64, t1: f64, centre: DVec2, radius: f64) -> Discs {
        let lin = |c: [f64; 2], t: f64| c[0] + c[1] * t;
        // S⁻¹·x at τ: each component (x/σx, y/σy) a ratio of linear
        // functions, monotone where σ > 0.
        let q = |t: f64| {
            DVec2::new(
                lin(self.x, t) / lin(self.sx, t),
                lin(self.y, t) / lin(self.sy, t),
            )
        };
        let at = |i: usize| {
            if i == DISCS {
                t1
            } else {
                t0 + (t1 - t0) * (i as f64 / DISCS as f64)
            }
        };
        let mut out = Discs {
            cuts: [0.0; DISCS + 1],
            centre: [DVec2::ZERO; DISCS],
            radius: [f64::INFINITY; DISCS],
            kept: 0,
        };
        for i in 0..=DISCS {
            out.cuts[i] = at(i);
        }
        let (mut ql, mut sl) = (q(t0), lin(self.sx, t0).min(lin(self.sy, t0)));
        // R(φ) at the pieces' middles, each the last turned by one piece's
        // φ (its rounding, some ulps a turn, well within the discs' room).
        let mut turn_m = DMat2::from_angle(lin(self.phi, 0.5 * (out.cuts[0] + out.cuts[1])));
        let step = DMat2::from_angle(self.phi[1] * (t1 - t0) / DISCS as f64);
        for i in 0..DISCS {
            let (l, h) = (out.cuts[i], out.cuts[i + 1]);
            let m = 0.5 * (l + h);
            let (qh, sh) = (q(h), lin(self.sx, h).min(lin(self.sy, h)));
            let qm = q(m);
            // |R(φ)q − R(φm)qm| ≤ |q − qm| + |R(φ) − R(φm)|·|qm|, the
            // first within the box of the ends' q (each component
            // monotone), the second at most 2|sin(Δφ/2)| ≤ |Δφ|.
            let far = (ql - qm).abs().max((qh - qm).abs()).length();
            let turn = if crate::mutant::active("twist_discs_unturned") {
                0.0
            } else {
                (self.phi[1] * (h - l) * 0.5).abs().min(2.0)
            };
            let r = far + turn * qm.length();
            out.centre[i] = turn_m * qm;
            turn_m = step * turn_m;
            // Where σ reaches zero (a scale of 0 at the top) the path
            // leaves for infinity: no bound.
            if sl > 0.0 && sh > 0.0 && r.is_finite() && out.centre[i].is_finite() {
                // Room for the rounding of the roots and of the edge test
                // that keeps them.
                out.radius[i] = r + 1e-9 * (r + qm.length());
            }
            if out.centre[i].distance(centre) <= out.radius[i] + radius * (1.0 + 1e-9)
                || out.radius[i] == f64::INFINITY
            {
                out.kept |= 1 << i;
            }
            (ql, sl) = (qh, sh);
        }
        out
    }

    /// Where the path can be within ρ₁ of the axis (scaled by σ), and
    /// where it can be at least ρ₀ from it: where ρ₀·min σ ≤ r(t) ≤ ρ₁·max
    /// σ, from r² − ρ₁²σ² ≤ 0 for σx or σy and ρ₀²σ² − r² ≤ 0 for σx or σy
    /// (quadratic inequalities, widened for rounding; under an even scale
    /// σx = σy, one of each).
    fn reach(&self, rho0: f64, rho1: f64) -> (Spans, Spans) {
        let (t0, t1, r2) = (self.t0, self.t1, self.r2);
        let near = |k: f64, q: Pol| Pol::comb(r2, q, 1.0, -k);
        let far = |k: f64, q: Pol| Pol::comb(q, r2, k, -1.0);
        if self.sx2.c == self.sy2.c {
            return (
                nonpositive(near(rho1 * rho1, self.sx2), t0, t1),
                nonpositive(far(rho0 * rho0, self.sx2), t0, t1),
            );
        }
        let upper = union2(
            nonpositive(near(rho1 * rho1, self.sx2), t0, t1),
            nonpositive(near(rho1 * rho1, self.sy2), t0, t1),
        );
        let lower = union2(
            nonpositive(far(rho0 * rho0, self.sx2), t0, t1),
            nonpositive(far(rho0 * rho0, self.sy2), t0, t1),
        );
        (upper, lower)
    }

    /// The roots of `side` in [t0, t1] where the path can reach the
    /// distances from the axis `reach` was found for ([`TwistPath::reach`]),
    /// over pieces in which φ (`turns` times it) turns by at most a radian.
    fn roots(
        &self,
        side: &Trig,
        reach: &(Spans, Spans),
        turns: f64,
        may: &impl Fn(f64, f64) -> bool,
        out: &mut SmallVec<[f64; 8]>,
    ) {
        let w = self.phi[1] * turns;
        for (l0, h0) in reach_overlaps(reach) {
            let pieces = ((w * (h0 - l0)).abs().ceil() as usize).clamp(1, 1 << 16);
            // G at the end of the last piece searched, the next one's start.
            let mut known: Option<(f64, f64)> = None;
            for i in 0..pieces {
                let l = l0 + (h0 - l0) * (i as f64 / pieces as f64);
                let h = if i + 1 == pieces {
                    h0
                } else {
                    l0 + (h0 - l0) * ((i + 1) as f64 / pieces as f64)
                };
                let gl = known.filter(|k| k.0 == l).map(|k| k.1);
                known = side.roots_after(l, h, gl, may, out).map(|gh| (h, gh));
            }
        }
        if self.tc != 0.0 {
            out.iter_mut().for_each(|t| *t += self.tc);
        }
        out.sort_by(f64::total_cmp);
        out.dedup();
    }
}

impl Solid for Twisted {
    const NAME: &'static str = "linear_extrude";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        // Heights from the bottom.
        let (o, d) = (q.o - DVec3::Z * self.z_lo(), q.d);
        if d.z.abs() <= super::lathe::FLAT * d.truncate().length() {
            // A straight path through the section at this height.
            if o.z <= 0.0 || o.z >= 1.0 {
                return;
            }
            let Some(f) = self.frame(o.z) else { return };
            let (o2, d2) = (f * o.truncate(), f * d.truncate());
            if d2 == DVec2::ZERO {
                if self.section.contains(o2) {
                    emit((f64::NEG_INFINITY, NO_PART, f64::INFINITY, NO_PART));
                }
                return;
            }
            match &self.section {
                TwistSection::Region(region) => {
                    for pair in region.crossings(o2, d2).chunks_exact(2) {
                        let ((s0, e0), (s1, e1)) = (pair[0], pair[1]);
                        if s0 < s1 {
                            emit((s0, SIDE + e0, s1, SIDE + e1));
                        }
                    }
                }
                TwistSection::Ellipse(e) => {
                    if let Some((s0, s1)) = line_ellipse(&Form::of(e), o2, d2) {
                        emit((s0, SIDE, s1, SIDE));
                    }
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
                .is_some_and(|f| self.section.contains(f * x.truncate()))
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

    /// The gradient of F(p(x)), F the section's side function (n·p − c,
    /// or the ellipse's form) with gradient n in the section: S⁻¹R(θz)ᵀn in
    /// x and y, and in z n·(θ·R′(θz)S⁻¹x + R(θz)·d(S⁻¹)/dz·x).
    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        let p = p - DVec3::Z * self.z_lo();
        match part {
            BOTTOM => DVec3::NEG_Z,
            TOP => DVec3::Z,
            k => {
                let s = self.sigma(p.z).max(DVec2::splat(1e-300));
                let rot = DMat2::from_angle(self.twist * p.z);
                let inv = DVec2::ONE / s;
                let x = p.truncate();
                let n = self.section_normal(rot * (x * inv), k);
                let xy = rot.transpose() * n * inv;
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
                .is_some_and(|f| self.section.contains(f * p.truncate()))
    }

    /// The box of all its sections ([`Twisted::swept`]).
    fn object_bounds(&self) -> Aabb {
        let (lo, hi) = self.swept(0.0, 1.0);
        let z = self.z_lo();
        Aabb::new(lo.extend(z), hi.extend(z + 1.0))
    }

    /// Along z, the box of the slab's sections (see [`Twisted::swept`]).
    fn slab_bounds(&self, axis: usize, lo: f64, hi: f64) -> Aabb {
        let z = self.z_lo();
        let (a, b) = ((lo - z).max(0.0), (hi - z).min(1.0));
        if axis != 2 || a > b {
            return super::solid::slab_of(self.object_bounds(), axis, lo, hi);
        }
        let (l, h) = self.swept(a, b);
        Aabb::new(l.extend(a + z), h.extend(b + z))
    }

    /// Its sections narrow (a taper) or turn (a twist) along z.
    fn narrowing_axis(&self) -> Option<usize> {
        Some(2)
    }

    /// Not computed: a twisted side's farthest point is not at a vertex.
    fn support(&self, _d: DVec3) -> Option<DVec3> {
        None
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        let mut out = match &self.section {
            TwistSection::Region(r) => vec![("edges", Param::Num(r.edges.len() as f64))],
            TwistSection::Ellipse(e) => {
                let (m, c) = (e.matrix2, e.translation);
                vec![
                    ("ellipse_xx", Param::Num(m.x_axis.x)),
                    ("ellipse_xy", Param::Num(m.y_axis.x)),
                    ("ellipse_yx", Param::Num(m.x_axis.y)),
                    ("ellipse_yy", Param::Num(m.y_axis.y)),
                    ("ellipse_cx", Param::Num(c.x)),
                    ("ellipse_cy", Param::Num(c.y)),
                ]
            }
        };
        out.extend([
            ("twist", Param::Num(self.twist.to_degrees())),
            ("scale_x", Param::Num(self.scale.x)),
            ("scale_y", Param::Num(self.scale.y)),
            ("center", Param::Bool(self.centered)),
        ]);
        out
    }

    /// POV-Ray has no twisted prism: the export stops POV-Ray with the
    /// reason rather than draw something else.
    fn pov(&self) -> String {
        "#error \"csgrt: a twisted or unevenly scaled linear_extrude has no POV-Ray equivalent\"\nsphere { <0, 0, 0>, 0".to_string()
    }
}

/// Where the line o + s·d (d ≠ 0) is inside the ellipse: the roots of
/// |M⁻¹(o + s·d − c)|² = 1, by the formula that does not cancel.
fn line_ellipse(f: &Form, o: DVec2, d: DVec2) -> Option<(f64, f64)> {
    let v = o - f.c;
    let (qa, qb, qc) = (d.dot(f.q * d), v.dot(f.q * d), v.dot(f.q * v) - 1.0);
    let disc = qb * qb - qa * qc;
    if disc.is_nan() || disc <= 0.0 {
        return None;
    }
    let k = -(qb + disc.sqrt().copysign(qb));
    let (x0, x1) = (k / qa, qc / k);
    Some((x0.min(x1), x0.max(x1)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::solid::Solid;

    /// A pentagon away from the axis, so that it sweeps a horn.
    fn horn(twist: f64, scale: DVec2) -> Twisted {
        let pts = (0..5)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 5.0;
                DVec2::new(3.0 + a.cos(), 0.5 + 1.5 * a.sin())
            })
            .collect();
        let region = Region::new(crate::plane::Outlines::polygons(vec![pts]));
        Twisted {
            section: TwistSection::Region(Arc::new(region)),
            twist,
            scale,
            centered: false,
        }
    }

    #[test]
    fn every_piece_of_a_path_lies_within_its_disc() {
        let mut rnd = crate::plane::tests::uniform(7);
        let mut checked = 0;
        for k in 0..600 {
            let scale = match k % 3 {
                0 => DVec2::ONE,
                1 => DVec2::splat(0.05 + rnd()),
                _ => DVec2::new(2.0 * rnd(), 2.0 * rnd()),
            };
            let tw = horn(12.0 * (rnd() - 0.5), scale);
            let o = DVec3::new(8.0 * rnd() - 4.0, 8.0 * rnd() - 4.0, 4.0 * rnd() - 2.0);
            let d = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
            if d.z.abs() < 1e-3 {
                continue;
            }
            let (tb, tt) = (-o.z / d.z, (1.0 - o.z) / d.z);
            let (t0, t1) = (tb.min(tt), tb.max(tt));
            let tc = t0 + (t1 - t0) * rnd();
            let path = TwistPath::new(&tw, o, d, t0, t1, tc);
            let discs = path.discs(path.t0, path.t1, DVec2::ZERO, f64::INFINITY);
            for i in 0..DISCS {
                for j in 0..=40 {
                    let (l, h) = (discs.cuts[i], discs.cuts[i + 1]);
                    let tau = l + (h - l) * (j as f64 / 40.0);
                    let x = o + d * (tau + tc);
                    let Some(f) = tw.frame(x.z.clamp(0.0, 1.0)) else {
                        continue;
                    };
                    let p = f * x.truncate();
                    let off = (p - discs.centre[i]).length();
                    assert!(
                        off <= discs.radius[i],
                        "{k}: piece {i} at {tau}: {off} > {}",
                        discs.radius[i]
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 100_000, "{checked}");
    }

    /// Every point of a twisted or tapered prism between two heights lies
    /// in [`Solid::slab_bounds`] of those heights, and the box of the whole
    /// height is the object box: 300 random horns (twists to ±10 radians,
    /// even and uneven scales, one of zero) and slabs, 4,000 random points
    /// each, kept where the solid holds them.
    #[test]
    fn a_slab_of_a_twist_lies_in_its_box() {
        let mut rnd = crate::plane::tests::uniform(23);
        let mut held = 0;
        for k in 0..300 {
            let scale = match k % 4 {
                0 => DVec2::ONE,
                1 => DVec2::splat(0.05 + rnd()),
                2 => DVec2::new(2.0 * rnd(), 2.0 * rnd()),
                _ => DVec2::ZERO,
            };
            let mut tw = horn(20.0 * (rnd() - 0.5), scale);
            tw.centered = k % 3 == 0;
            let whole = tw.object_bounds();
            let z0 = tw.z_lo();
            assert_eq!(tw.slab_bounds(2, z0, z0 + 1.0), whole, "{k}");
            let (a, b) = (rnd(), rnd());
            let (lo, hi) = (z0 + a.min(b), z0 + a.max(b));
            let slab = tw.slab_bounds(2, lo, hi);
            for _ in 0..4000 {
                let p = whole.min + (whole.max - whole.min) * DVec3::new(rnd(), rnd(), rnd());
                let p = DVec3::new(p.x, p.y, lo + (hi - lo) * rnd());
                if tw.contains(p) {
                    held += 1;
                    assert!(
                        slab.min.cmple(p).all() && p.cmple(slab.max).all(),
                        "{k}: {p} outside {slab:?} ({lo}..{hi})"
                    );
                }
            }
        }
        assert!(held > 50_000, "{held}");
    }

    #[test]
    fn the_box_of_a_twist_holds_it_and_untapered_touches_it() {
        let mut rnd = crate::plane::tests::uniform(11);
        for k in 0..200 {
            let scale = if k % 2 == 0 {
                DVec2::ONE
            } else {
                DVec2::new(2.0 * rnd(), 2.0 * rnd())
            };
            let tw = horn(20.0 * (rnd() - 0.5), scale);
            let b = tw.object_bounds();
            for (axis, sign) in [
                (DVec3::X, 1.0),
                (DVec3::Y, 1.0),
                (DVec3::X, -1.0),
                (DVec3::Y, -1.0),
            ] {
                let far = tw.far_point(axis * sign).dot(axis);
                let side = if sign > 0.0 {
                    b.max.dot(axis)
                } else {
                    b.min.dot(axis)
                };
                // The box reaches at least the far point; without a taper,
                // the corners' arcs are the solid's own extremes.
                assert!(sign * (side - far) >= -1e-12, "{k}: {side} inside {far}");
                if scale == DVec2::ONE {
                    assert!((side - far).abs() <= 1e-7, "{k}: {side} vs {far}");
                }
            }
        }
    }
}
