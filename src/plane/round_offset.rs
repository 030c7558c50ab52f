//! A region of the plane offset by a distance with round joins — OpenSCAD's
//! `offset(r)` — exactly, whatever its edges (lines and quadratic Bézier
//! curves: a TrueType glyph's).
//!
//! Grown by r > 0 it is R ⊕ D(r) = R ∪ {p : dist(p, ∂R) ≤ r}; shrunk by
//! r < 0 it is R ⊖ D(|r|) = {p ∈ R : dist(p, ∂R) ≥ |r|}. Either way its
//! boundary lies where dist(p, ∂R) = |r|: on the curves each edge's points
//! trace at distance |r| along its normals (the offset curves) or on the
//! circles of radius |r| about its vertices. ∂R is the union of the edges
//! (even-odd outlines: every edge bounds the region), so a line's spans
//! are found by (1) the places where it meets any of those curves and
//! circles — candidates, some of which are not on the boundary — and (2)
//! the side of each stretch between consecutive candidates, decided at its
//! middle: inside R (the parity of R's own crossings along the same line)
//! and within |r| of an edge. Whether or not a candidate lies on the
//! boundary, the stretches' sides are right, and the boundary is among
//! the candidates.
//!
//! Where the line o + s·d meets the offset curve of the edge B(u): with
//! w = B(u) − o and b = B′(u), the point B(u) ± |r|·b⊥/|b| is on the line
//! when d×w·|b| = ∓|r|·(d·b), so u is a root of
//! (d×w)²·|b|² − r²·(d·b)², of degree 6 for a quadratic (a straight edge's
//! two offset lines are met directly). Each root's point is projected on
//! the line. A vertex's circle is met at the roots of a quadratic in s.
//!
//! The normal at a boundary point p is (p − q)/|r| with q the point of ∂R
//! nearest p (turned inward for a shrunk region), found anew from the
//! point among every edge near it, so it never depends on which candidate
//! the side changed at.

use super::{Ctrl, Curve, EdgeTree, Region};
use crate::math::poly::{self, roots_in};
use glam::{DVec2, DVec3};
use smallvec::SmallVec;

/// Edges checked one by one below this many; above, a box tree.
const OFFSET_SCAN_EDGES: usize = 16;

/// A region offset with round joins (see the module's text).
#[derive(Clone, Debug, PartialEq)]
pub struct RoundOffset {
    pub region: Region,
    /// The signed distance: > 0 grown, < 0 shrunk (never 0).
    pub r: f64,
    /// Each edge's box grown by a little more than |r| (it holds every
    /// point within |r|).
    boxes: Vec<(DVec2, DVec2)>,
    tree: Option<EdgeTree>,
    /// The box of the offset region.
    pub lo: DVec2,
    pub hi: DVec2,
}

/// Whether an edge can be offset here: straight or quadratic.
pub fn offsettable(c: Ctrl) -> bool {
    !matches!(c, Ctrl::Cubic(..))
}

impl RoundOffset {
    /// `region` offset by `r` (not zero; no cubic edges).
    pub fn new(region: Region, r: f64) -> RoundOffset {
        let k = r.abs();
        // A filter only: widened past |r| by far more than the rounding of
        // a boundary point, which lies at |r| from its edge.
        let size = region.lo.abs().max(region.hi.abs()).max_element();
        let pad = k * (1.0 + 1e-9) + 1e-9 * size;
        let boxes: Vec<(DVec2, DVec2)> = region
            .edges
            .iter()
            .zip(&region.ctrl)
            .map(|(&(a, b), c)| {
                let (lo, hi) = c.bounds(a, b);
                (lo - DVec2::splat(pad), hi + DVec2::splat(pad))
            })
            .collect();
        let tree = (boxes.len() > OFFSET_SCAN_EDGES).then(|| EdgeTree::new(&boxes));
        // Grown, the extent moves out by exactly r; shrunk, it is within R's.
        let (lo, hi) = if r > 0.0 {
            (region.lo - DVec2::splat(k), region.hi + DVec2::splat(k))
        } else {
            (region.lo, region.hi)
        };
        RoundOffset {
            region,
            r,
            boxes,
            tree,
            lo,
            hi,
        }
    }

    /// The edges whose grown boxes the line ℓ·(x, y, 1) = 0 may meet.
    fn near(&self, line: DVec3) -> SmallVec<[u32; 32]> {
        let mut ids = SmallVec::new();
        match &self.tree {
            Some(t) => t.visit(line, &mut |k| ids.push(k)),
            None => {
                for (k, &(lo, hi)) in self.boxes.iter().enumerate() {
                    let (mut pos, mut neg) = (true, true);
                    for c in [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)] {
                        let v = line.x * c.x + line.y * c.y + line.z;
                        let tol =
                            1e-14 * ((line.x * c.x).abs() + (line.y * c.y).abs() + line.z.abs());
                        pos &= v > tol;
                        neg &= v < -tol;
                    }
                    if !(pos || neg) {
                        ids.push(k as u32);
                    }
                }
            }
        }
        ids
    }

    /// The squared distance from `p` to edge `e`, and the nearest point.
    pub fn nearest_on(&self, e: usize, p: DVec2) -> (f64, DVec2) {
        let (a, b) = self.region.edges[e];
        match self.region.ctrl[e] {
            Ctrl::Line => {
                let ab = b - a;
                let ll = ab.length_squared();
                let u = if ll > 0.0 {
                    ((p - a).dot(ab) / ll).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let q = a + ab * u;
                ((p - q).length_squared(), q)
            }
            c => {
                // (B(u) − p)·B′(u) = 0 at an inner nearest point.
                let k = Curve::new(a, c, b, p).k;
                let f = poly::poly(&[
                    k[0].dot(k[1]),
                    k[1].dot(k[1]) + 2.0 * k[0].dot(k[2]),
                    3.0 * k[1].dot(k[2]),
                    2.0 * k[2].dot(k[2]),
                ]);
                let curve = Curve { k, degree: 2 };
                let mut best = ((a - p).length_squared(), a);
                let eb = (b - p).length_squared();
                if eb < best.0 {
                    best = (eb, b);
                }
                let mut roots = [0.0; poly::MAX_DEGREE];
                let n = roots_in(&f, 3, 0.0, 1.0, &mut roots);
                for &u in &roots[..n] {
                    let q = curve.at(u);
                    let e2 = q.length_squared();
                    if e2 < best.0 {
                        best = (e2, q + p);
                    }
                }
                best
            }
        }
    }

    /// The squared distance from `p` to the nearest of `edges` (those whose
    /// grown boxes hold p), with that edge; (∞, 0) when none is within |r|.
    fn nearest_of(&self, edges: &[u32], p: DVec2) -> (f64, u32, DVec2) {
        let mut best = (f64::INFINITY, 0, p);
        for &e in edges {
            let (lo, hi) = self.boxes[e as usize];
            if p.cmplt(lo).any() || p.cmpgt(hi).any() {
                continue;
            }
            let (d2, q) = self.nearest_on(e as usize, p);
            if d2 < best.0 {
                best = (d2, e, q);
            }
        }
        best
    }

    /// Whether `p` is within |r| of an edge among `edges` (closer than |r|
    /// when not `closed`).
    fn within(&self, edges: &[u32], p: DVec2, closed: bool) -> bool {
        let r2 = self.r * self.r;
        edges.iter().any(|&e| {
            let (lo, hi) = self.boxes[e as usize];
            if p.cmplt(lo).any() || p.cmpgt(hi).any() {
                return false;
            }
            let d2 = self.nearest_on(e as usize, p).0;
            if closed {
                d2 <= r2
            } else {
                d2 < r2
            }
        })
    }

    /// The edges whose grown boxes hold `p`.
    fn near_point(&self, p: DVec2) -> SmallVec<[u32; 32]> {
        self.near(DVec3::new(0.0, 1.0, -p.y))
    }

    /// Whether `p` is inside (the boundary counts as inside).
    pub fn contains(&self, p: DVec2) -> bool {
        let near = self.near_point(p);
        let (d2, _, _) = self.nearest_of(&near, p);
        let r2 = self.r * self.r;
        if self.r > 0.0 {
            d2 <= r2 || self.region.contains(p)
        } else {
            d2 >= r2 && self.region.contains(p)
        }
    }

    /// The unit outward normal at a boundary point `p`: away from the
    /// nearest point of the outlines (towards it, shrunk).
    pub fn normal_at(&self, p: DVec2) -> DVec2 {
        let near = self.near_point(p);
        let (_, _, q) = self.nearest_of(&near, p);
        let n = (p - q).normalize_or_zero();
        if self.r > 0.0 {
            n
        } else {
            -n
        }
    }

    /// The point farthest along `dir` of the grown region (`None` shrunk:
    /// not known exactly).
    pub fn farthest(&self, dir: DVec2) -> Option<DVec2> {
        (self.r > 0.0).then(|| self.region.farthest(dir) + dir.normalize_or_zero() * self.r)
    }

    /// The spans `(s_in, edge_in, s_out, edge_out)` of the line `o + s·d`
    /// (d ≠ 0) inside, sorted.
    pub fn spans(&self, o: DVec2, d: DVec2, mut emit: impl FnMut(f64, u32, f64, u32)) {
        // A direction of no normal size: scaled exactly (see `unit_scale`).
        let (d, (k0, k1)) = super::unit_scale(d);
        let mut emit = |s0: f64, e0, s1: f64, e1| emit(s0 / k0 / k1, e0, s1 / k0 / k1, e1);
        let n = d.perp();
        let k = self.r.abs();
        // An edge lies in the hull of its points and control points: all
        // of them farther than |r| on one side, no point of the line is
        // within |r| of it (the margin far above the rounding of the side
        // values).
        let reach = k * n.length() * (1.0 + 1e-9);
        let mut near = self.near(DVec3::new(n.x, n.y, -o.dot(n)));
        near.retain(|e| {
            let (a, b) = self.region.edges[*e as usize];
            let side = |p: DVec2| (p - o).dot(n);
            let tol = 1e-12 * (a.abs().max(b.abs()).max(o.abs()).max_element() * n.length());
            let (mut lo, mut hi) = (side(a).min(side(b)), side(a).max(side(b)));
            for p in self.region.ctrl[*e as usize].points() {
                lo = lo.min(side(p));
                hi = hi.max(side(p));
            }
            lo <= reach + tol && hi >= -reach - tol
        });
        if near.is_empty() {
            // Within |r| of no edge: a line meeting R crosses an edge, so it
            // meets neither R nor the points near its outline.
            return;
        }
        let dd = d.length_squared();
        let mut cuts: SmallVec<[(f64, u32); 64]> = SmallVec::new();
        for &e in &near {
            let (a, b) = self.region.edges[e as usize];
            // The circle about the edge's start.
            let rel = a - o;
            let sc = rel.dot(d) / dd;
            let h2 = (rel - d * sc).length_squared();
            if h2 < k * k {
                let half = ((k * k - h2) / dd).sqrt();
                cuts.push((sc - half, e));
                cuts.push((sc + half, e));
            }
            match self.region.ctrl[e as usize] {
                Ctrl::Line => {
                    let nrm = (b - a).perp().normalize_or_zero();
                    for side in [k, -k] {
                        let (p, q) = (a + nrm * side, b + nrm * side);
                        let (sp, sq) = ((p - o).dot(n), (q - o).dot(n));
                        if (sp > 0.0) == (sq > 0.0) || sp == sq {
                            continue;
                        }
                        let x = p + (q - p) * (sp / (sp - sq));
                        cuts.push(((x - o).dot(d) / dd, e));
                    }
                }
                c => {
                    // About the line's point nearest the edge's middle, so
                    // that B(u) − o stays the size of the edge.
                    let mid = 0.5 * (a + b);
                    let s0 = (mid - o).dot(d) / dd;
                    let curve = Curve::new(a, c, b, o + d * s0);
                    offset_crossings(&curve, n, k, |p| cuts.push((s0 + p.dot(d) / dd, e)));
                }
            }
        }
        if cuts.is_empty() {
            return;
        }
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        let rc = self.region.crossings(o, d);
        let in_region = |s: f64| rc.partition_point(|c| c.0 < s) % 2 == 1;
        let grown = self.r > 0.0;
        let inside = |s: f64| {
            let p = o + d * s;
            if grown {
                in_region(s) || self.within(&near, p, true)
            } else {
                in_region(s) && !self.within(&near, p, false)
            }
        };
        // Outside before the first candidate and after the last.
        let mut open: Option<(f64, u32)> = None;
        let mut i = 0;
        while i < cuts.len() {
            let (s, e) = cuts[i];
            // The next distinct candidate.
            let mut j = i + 1;
            while j < cuts.len() && cuts[j].0 == s {
                j += 1;
            }
            let now = j < cuts.len() && inside(0.5 * (s + cuts[j].0));
            match (open, now) {
                (None, true) => open = Some((s, e)),
                (Some((s_in, e_in)), false) => {
                    emit(s_in, e_in, s, e);
                    open = None;
                }
                _ => {}
            }
            i = j;
        }
    }
}

/// Calls `f` with each point where the offset curves B(u) ± k·ν(u) of the
/// quadratic `curve` (ν the unit left normal, k > 0) cross the line through
/// the curve's origin with normal `nl`, u in (0, 1).
///
/// Along either curve, h_σ(u) = nl·(B(u) + σ·k·ν(u)) is the line's side.
/// Its point moves along B′(u)·(1 − σ·k·κ(u)), κ the signed curvature
/// (b×b′)/|b|³, b = B′: h_σ turns only where nl·b(u) = 0 (linear in u) or
/// where κ(u) = σ/k, i.e. |b(u)|² = (σ·k·(b×b′))^(2/3) (quadratic in u; b×b′
/// is constant for a quadratic). Between those at most three points h_σ is
/// monotonic, and each stretch whose ends differ in sign holds one root,
/// bracketed and refined. The two curves are kept apart, so a line along a
/// normal of the curve (both its points at one u) loses neither.
fn offset_crossings(curve: &Curve, nl: DVec2, k: f64, mut f: impl FnMut(DVec2)) {
    let kk = curve.k;
    let (b0, b1) = (kk[1], 2.0 * kk[2]);
    let cross = b0.perp_dot(b1);
    if cross == 0.0 {
        // Control points on one line: the curve runs along a segment
        // (folding back, maybe); its offset lines between its extreme
        // points, whose circles its neighbours or these cover.
        let dir = if b1 != DVec2::ZERO { b1 } else { b0 };
        let (mut lo, mut hi) = (curve.at(0.0), curve.at(1.0));
        if lo.dot(dir) > hi.dot(dir) {
            std::mem::swap(&mut lo, &mut hi);
        }
        curve.turning(dir, |u| {
            let q = curve.at(u);
            if q.dot(dir) < lo.dot(dir) {
                lo = q;
            }
            if q.dot(dir) > hi.dot(dir) {
                hi = q;
            }
        });
        let Some(nrm) = (hi - lo).perp().try_normalize() else {
            return;
        };
        for side in [k, -k] {
            let (p, q) = (lo + nrm * side, hi + nrm * side);
            let (sp, sq) = (p.dot(nl), q.dot(nl));
            if (sp > 0.0) != (sq > 0.0) && sp != sq {
                f(p + (q - p) * (sp / (sp - sq)));
            }
        }
        // The extreme points' circles (not always a vertex's).
        for e in [lo, hi] {
            circle_points(e, k, nl, &mut f);
        }
        return;
    }
    let point = |u: f64, sigma: f64| {
        let t = curve.tangent(u);
        curve.at(u) + t.perp() * (sigma * k / t.length())
    };
    let sides: &[f64] = if crate::mutant::active("offset_one_side") {
        &[-1.0]
    } else {
        &[1.0, -1.0]
    };
    for &sigma in sides {
        let mut crit: SmallVec<[f64; 4]> = SmallVec::new();
        let (na, nb) = (nl.dot(b0), nl.dot(b1));
        if nb != 0.0 {
            crit.push(-na / nb);
        }
        if sigma * cross > 0.0 {
            let l = (sigma * k * cross).powf(2.0 / 3.0);
            let q = poly::poly(&[b0.dot(b0) - l, 2.0 * b0.dot(b1), b1.dot(b1)]);
            let mut roots = [0.0; poly::MAX_DEGREE];
            let n = roots_in(&q, 2, 0.0, 1.0, &mut roots);
            crit.extend_from_slice(&roots[..n]);
        }
        crit.retain(|u| *u > 0.0 && *u < 1.0);
        crit.sort_by(f64::total_cmp);
        let h = |u: f64| nl.dot(point(u, sigma));
        let mut u0 = 0.0;
        let mut h0 = h(0.0);
        for u1 in crit.iter().copied().chain(std::iter::once(1.0)) {
            let h1 = h(u1);
            if (h0 < 0.0) != (h1 < 0.0) {
                let u = bracketed(&h, u0, u1, h0);
                f(point(u, sigma));
            }
            u0 = u1;
            h0 = h1;
        }
    }
}

/// The points where the circle of radius k about `c` meets the line through
/// the origin with normal `nl` (nothing when it misses).
fn circle_points(c: DVec2, k: f64, nl: DVec2, f: &mut impl FnMut(DVec2)) {
    let ln = nl.length();
    let h = c.dot(nl) / ln;
    if h.abs() < k {
        let foot = c - nl * (h / ln);
        let run = nl.perp() * ((k * k - h * h).sqrt() / ln);
        f(foot + run);
        f(foot - run);
    }
}

/// The root in [a, b] of `h`, monotonic there with h(a) = ha and h(b) of
/// the other sign: the Illinois variant of false position, kept inside the
/// bracket, to the last bits of u.
fn bracketed(h: &impl Fn(f64) -> f64, mut a: f64, mut b: f64, mut ha: f64) -> f64 {
    let mut hb = h(b);
    let mut side = 0;
    for _ in 0..200 {
        let mut x = (a * hb - b * ha) / (hb - ha);
        if !(x > a && x < b) {
            x = 0.5 * (a + b);
        }
        if b - a <= 4.0 * f64::EPSILON * a.abs().max(b.abs()).max(f64::MIN_POSITIVE) {
            return x;
        }
        let hx = h(x);
        if hx == 0.0 {
            return x;
        }
        if (hx < 0.0) == (ha < 0.0) {
            a = x;
            ha = hx;
            if side == -1 {
                hb *= 0.5;
            }
            side = -1;
        } else {
            b = x;
            hb = hx;
            if side == 1 {
                ha *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::Outlines;

    /// A closed outline of quadratic curves and lines: a rounded blob.
    fn blob() -> Outlines {
        let loops = vec![vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 3.0),
            DVec2::new(2.0, 1.5),
            DVec2::new(0.0, 3.0),
        ]];
        let ctrl = vec![vec![
            Ctrl::Line,
            Ctrl::Quad(DVec2::new(5.5, 1.5)),
            Ctrl::Quad(DVec2::new(3.0, 3.5)),
            Ctrl::Line,
            Ctrl::Quad(DVec2::new(-1.0, 1.0)),
        ]];
        Outlines { loops, ctrl }
    }

    /// The distance from p to the outline by dense sampling (every edge at
    /// 2,001 parameters, then the best refined by golden-section search):
    /// an independent reference.
    fn sampled_distance(o: &Outlines, p: DVec2) -> f64 {
        let mut best = f64::INFINITY;
        for (a, c, b) in o.edges() {
            let curve = Curve::new(a, c, b, DVec2::ZERO);
            let f = |u: f64| (curve.at(u) - p).length();
            let m = 2_000;
            let (mut bi, mut bv) = (0, f64::INFINITY);
            for i in 0..=m {
                let v = f(i as f64 / m as f64);
                if v < bv {
                    (bi, bv) = (i, v);
                }
            }
            let (mut lo, mut hi) = (
                (bi.max(1) - 1) as f64 / m as f64,
                ((bi + 1).min(m)) as f64 / m as f64,
            );
            for _ in 0..100 {
                let (x1, x2) = (lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo));
                if f(x1) < f(x2) {
                    hi = x2;
                } else {
                    lo = x1;
                }
            }
            best = best.min(bv).min(f(0.5 * (lo + hi)));
        }
        best
    }

    #[test]
    fn spans_agree_with_sampled_distances() {
        let o = blob();
        let mut next = crate::plane::tests::uniform(0x2545_f491_4f6c_dd1du64);
        for r in [0.4, 1.3, -0.3, -0.7] {
            let off = RoundOffset::new(Region::new(o.clone()), r);
            for _ in 0..200 {
                let a = DVec2::new(next() * 10.0 - 3.0, next() * 10.0 - 3.5);
                let b = DVec2::new(next() * 10.0 - 3.0, next() * 10.0 - 3.5);
                let d = b - a;
                let mut spans = Vec::new();
                off.spans(a, d, |s0, _, s1, _| spans.push((s0, s1)));
                for w in spans.windows(2) {
                    assert!(w[0].1 <= w[1].0, "{spans:?}");
                }
                // Every span end is at distance |r| from the outline.
                for &(s0, s1) in &spans {
                    assert!(s0 < s1);
                    for s in [s0, s1] {
                        let dist = sampled_distance(&o, a + d * s);
                        assert!(
                            (dist - r.abs()).abs() < 1e-7,
                            "r {r}: end at distance {dist}"
                        );
                    }
                }
                // Points along the line: inside exactly where a span holds
                // them, by the sampled distance and the region's parity.
                for i in 0..60 {
                    let s = -0.5 + 2.0 * (i as f64 + next()) / 60.0;
                    let p = a + d * s;
                    let dist = sampled_distance(&o, p);
                    if (dist - r.abs()).abs() < 1e-6 {
                        continue;
                    }
                    let want = if r > 0.0 {
                        o.contains(p) || dist < r
                    } else {
                        o.contains(p) && dist > -r
                    };
                    let got = spans.iter().any(|&(s0, s1)| s0 <= s && s <= s1);
                    assert_eq!(got, want, "r {r}, s {s}, distance {dist}");
                    assert_eq!(off.contains(p), want);
                }
            }
        }
    }

    #[test]
    fn normals_point_away_from_the_nearest_point() {
        let o = blob();
        let off = RoundOffset::new(Region::new(o.clone()), 0.5);
        // Straight right of the quadratic's far point (x ≈ 4.75 at y = 1.5):
        // the normal is +x.
        let mut hit = None;
        off.spans(
            DVec2::new(10.0, 1.5),
            DVec2::new(-1.0, 0.0),
            |s0, _, _, _| {
                hit.get_or_insert(s0);
            },
        );
        let p = DVec2::new(10.0, 1.5) + DVec2::new(-1.0, 0.0) * hit.unwrap();
        assert!((p.x - 5.25).abs() < 1e-12, "{p}");
        assert!((off.normal_at(p) - DVec2::X).length() < 1e-9);
    }

    /// A point on the boundary moved off it by 32 ulps along the normal
    /// (as a shadow ray's origin is) and a line leaving from it: no
    /// boundary within 1e-6 (a zero normal, where a rounded point fell
    /// outside every edge's box, gave such self-hits).
    #[test]
    fn a_line_leaving_the_boundary_meets_nothing_near() {
        let o = blob();
        let mut next = crate::plane::tests::uniform(0x1234_5678_9abc_def1u64);
        for r in [0.4, -0.3] {
            let off = RoundOffset::new(Region::new(o.clone()), r);
            for _ in 0..2000 {
                let a = DVec2::new(next() * 10.0 - 3.0, next() * 10.0 - 3.5);
                let d = (DVec2::new(next() * 10.0 - 3.0, next() * 10.0 - 3.5) - a).normalize();
                let mut first = None;
                off.spans(a, d, |s0, _, _, _| {
                    first.get_or_insert(s0);
                });
                let Some(s) = first else { continue };
                let p = a + d * s;
                let n = off.normal_at(p);
                assert!((n.length() - 1.0).abs() < 1e-12, "{p} {n}");
                let from = p + n * (32.0 * f64::EPSILON * 10.0);
                let ang = next() * std::f64::consts::TAU;
                let l = DVec2::new(ang.cos(), ang.sin());
                let l = if l.dot(n) < 0.0 { -l } else { l };
                off.spans(from, l, |s0, _, s1, _| {
                    assert!(!(s0 > 0.0 && s0 < 1e-6 || s1 > 0.0 && s1 < 1e-6), "{p} {l}");
                });
            }
        }
    }
}
