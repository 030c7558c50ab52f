//! What a 2-D hull is the hull of: points, discs and arcs of circles.
//!
//! A hull of straight polygons and circles, and of their unions,
//! intersections and differences, is a convex region whose boundary runs
//! straight between points of the shapes' boundaries and along arcs of
//! their circles. The hull of a region is the hull of its boundary, so a
//! combination is read as the pieces of its boundary: every polygon edge
//! and every circle, cut where it crosses another, each piece kept where
//! the combination lies on one side of it and not on the other (tested just
//! off its middle, on both sides, so a piece on an edge of another shape is
//! judged by what is really there). A kept piece gives its ends as points;
//! a kept arc with the region on the centre's side (a convex arc) is also a
//! [`Site`] of the hull, as a piece of a circle that the hull's boundary
//! can follow.
//!
//! The hull is then [`super::hull::arc_hull`]'s polygon through the
//! points where its boundary leaves and meets the arcs, with each arc's
//! own cap (the disc beyond the arc's chord) joined to it: the part of the
//! hull outside the polygon is the caps of the arcs it follows, and each
//! cap lies in the hull, as the hull of its arc.

use super::figure::{is_circle, Figure};
use crate::math::boolean::Op;
use glam::DVec2;
use std::f64::consts::TAU;

/// A piece of what a hull is the hull of: the disc of radius r about c
/// (r = 0: a point), or only its arc whose outward normals run from the
/// angle `from` over `span` radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Site {
    pub c: DVec2,
    pub r: f64,
    pub arc: Option<(f64, f64)>,
}

impl Site {
    pub fn point(p: DVec2) -> Site {
        Site {
            c: p,
            r: 0.0,
            arc: None,
        }
    }

    pub fn disc(c: DVec2, r: f64) -> Site {
        Site { c, r, arc: None }
    }

    /// The point of its circle whose outward normal is at angle `a`.
    pub fn at(&self, a: f64) -> DVec2 {
        self.c + DVec2::from_angle(a) * self.r
    }

    /// The points of its circle that can be extreme along an axis: an
    /// arc's ends and the axis points it faces (a disc's four).
    pub fn extremes(&self) -> Vec<DVec2> {
        let mut out: Vec<DVec2> = match self.arc {
            Some((from, span)) => vec![self.at(from), self.at(from + span)],
            None => Vec::new(),
        };
        for k in 0..4 {
            let a = k as f64 * TAU / 4.0;
            if self.faces(a, 0.0) {
                out.push(self.at(a));
            }
        }
        out
    }

    /// Whether the outward normal at angle `a` is one of the site's (any is
    /// a whole disc's), within `tol` radians.
    pub fn faces(&self, a: f64, tol: f64) -> bool {
        match self.arc {
            None => true,
            Some((from, span)) => {
                let past = (a - from).rem_euclid(TAU);
                past <= span + tol || past >= TAU - tol
            }
        }
    }

    /// The arc's cap, the part of the disc on the arc's side of its chord,
    /// as the disc and the arc's box cut by the chord's line (the whole
    /// disc for a circle). The cap is the hull of the arc, so it lies in
    /// that box, and the box's every side touches the arc: the cap's box
    /// is the arc's own, and a hull framed by its parts' boxes is framed
    /// exactly.
    pub fn cap(&self) -> Figure {
        let disc = Figure::disc(self.c, self.r);
        let Some((from, span)) = self.arc else {
            return disc;
        };
        let e0 = self.at(from);
        let (lo, hi) = bounds(&self.extremes());
        let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        // The box on the arc's side of the chord.
        let m = DVec2::from_angle(from + span / 2.0);
        let poly = clip(&corners, |p| (p - e0).dot(m));
        if poly.len() < 3 {
            return disc;
        }
        Figure::Op(
            Op::Intersection,
            vec![
                disc,
                Figure::Polygon(crate::plane::Outlines::polygons(vec![poly])),
            ],
        )
    }
}

/// The box (lower and upper corner) of some points.
pub fn bounds(pts: &[DVec2]) -> (DVec2, DVec2) {
    let lo = pts.iter().fold(DVec2::INFINITY, |a, &p| a.min(p));
    let hi = pts.iter().fold(DVec2::NEG_INFINITY, |a, &p| a.max(p));
    (lo, hi)
}

/// The part of a convex polygon where `side` is not negative
/// (Sutherland–Hodgman; `side` affine).
pub fn clip(poly: &[DVec2], side: impl Fn(DVec2) -> f64) -> Vec<DVec2> {
    let mut out = Vec::new();
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            out.push(a + (b - a) * (sa / (sa - sb)));
        }
    }
    out
}

/// The most boundary pieces (polygon edges and circles) a combination may
/// have to be read here: each is cut at every other (n² tests), and each
/// stretch tested against the whole tree (n² again, times the cuts).
pub const MAX_PIECES: usize = 20_000;

/// Whether `f` is made of pieces [`strokes`] reads but has more than
/// [`MAX_PIECES`] of them.
pub fn too_many_pieces(f: &Figure) -> bool {
    let mut all = Vec::new();
    pieces(f, &mut all) && all.len() > MAX_PIECES
}

/// Adds to `out` the sites `f`'s hull is the hull of: its circles and its
/// polygons' corners, or for a combination other than a union, the pieces
/// of its boundary (above). False for a shape that has others (an ellipse,
/// a curve, a projection, an offset) or too many pieces.
pub fn sites(f: &Figure, out: &mut Vec<Site>) -> bool {
    match f {
        Figure::Ellipse(e) if is_circle(e.matrix2) => {
            out.push(Site::disc(e.translation, e.matrix2.x_axis.length()));
            true
        }
        Figure::Polygon(o) if !o.curved() => {
            out.extend(o.loops.iter().flatten().map(|&p| Site::point(p)));
            true
        }
        Figure::Op(Op::Union, kids) | Figure::Hull(kids) => kids.iter().all(|k| sites(k, out)),
        Figure::Op(..) => boundary(f, out),
        _ => false,
    }
}

/// A piece of a boundary: a straight edge, or a whole circle.
#[derive(Clone, Copy)]
enum SitePiece {
    Edge(DVec2, DVec2),
    Circle(DVec2, f64),
}

/// The edges and circles of the leaves of `f`; false for any other leaf.
fn pieces(f: &Figure, out: &mut Vec<SitePiece>) -> bool {
    match f {
        Figure::Ellipse(e) if is_circle(e.matrix2) => {
            out.push(SitePiece::Circle(e.translation, e.matrix2.x_axis.length()));
            true
        }
        Figure::Polygon(o) if !o.curved() => {
            for l in &o.loops {
                for (i, &a) in l.iter().enumerate() {
                    out.push(SitePiece::Edge(a, l[(i + 1) % l.len()]));
                }
            }
            true
        }
        Figure::Op(_, kids) => kids.iter().all(|k| pieces(k, out)),
        _ => false,
    }
}

/// Whether p is in `f` (made of `pieces`' leaves only).
pub fn inside(f: &Figure, p: DVec2) -> bool {
    match f {
        Figure::Ellipse(e) => e.inverse().transform_point2(p).length_squared() <= 1.0,
        Figure::Polygon(o) => o.contains(p),
        Figure::Op(Op::Union, kids) => kids.iter().any(|k| inside(k, p)),
        Figure::Op(Op::Intersection, kids) => kids.iter().all(|k| inside(k, p)),
        Figure::Op(Op::Difference, kids) => {
            kids.first().is_some_and(|k| inside(k, p)) && !kids[1..].iter().any(|k| inside(k, p))
        }
        // A drawing's even-odd paths: in an odd number of them.
        Figure::Op(Op::Xor, kids) => {
            let n = kids.iter().filter(|k| inside(k, p)).count();
            // The fault: read as their union.
            if crate::mutant::active("sites_xor_united") {
                return n > 0;
            }
            n % 2 == 1
        }
        _ => false,
    }
}

/// Where the line a + u·(b − a) meets the circle (c, r): the u of both
/// points (none where it misses).
fn line_circle(a: DVec2, b: DVec2, c: DVec2, r: f64) -> Vec<f64> {
    let d = b - a;
    let f = a - c;
    let (qa, qb, qc) = (
        d.length_squared(),
        2.0 * f.dot(d),
        f.length_squared() - r * r,
    );
    let disc = qb * qb - 4.0 * qa * qc;
    if qa == 0.0 || disc < 0.0 {
        return Vec::new();
    }
    let s = disc.sqrt();
    // The root of larger size first, the other from the product.
    let q = -0.5 * (qb + s.copysign(qb));
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / qa, qc / q]
}

/// Adds the pieces of `f`'s boundary (above) to `out` as sites.
fn boundary(f: &Figure, out: &mut Vec<Site>) -> bool {
    let Some((strokes, _)) = strokes(f) else {
        return false;
    };
    for s in strokes {
        match s {
            Stroke::Line(p, q) => {
                out.push(Site::point(p));
                out.push(Site::point(q));
            }
            Stroke::Arc {
                c,
                r,
                from,
                span,
                convex,
            } => {
                if span >= TAU {
                    if convex {
                        out.push(Site::disc(c, r));
                    }
                    continue;
                }
                out.push(Site::point(s.start()));
                out.push(Site::point(s.end()));
                if convex {
                    out.push(Site {
                        c,
                        r,
                        arc: Some((from, span)),
                    });
                }
            }
        }
    }
    true
}

/// A piece of a combination's boundary, running with the shape on its
/// left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stroke {
    /// A stretch of a polygon edge, from the first point to the second.
    Line(DVec2, DVec2),
    /// The arc of the circle (c, r) over the angles from `from` to `from +
    /// span` (span in (0, 2π]; 2π: the whole circle), run counter-clockwise
    /// when the shape is on the centre's side (`convex`), else clockwise.
    Arc {
        c: DVec2,
        r: f64,
        from: f64,
        span: f64,
        convex: bool,
    },
}

impl Stroke {
    /// Where it starts.
    pub fn start(&self) -> DVec2 {
        match *self {
            Stroke::Line(p, _) => p,
            Stroke::Arc {
                c,
                r,
                from,
                span,
                convex,
            } => c + DVec2::from_angle(if convex { from } else { from + span }) * r,
        }
    }

    /// Where it ends.
    pub fn end(&self) -> DVec2 {
        match *self {
            Stroke::Line(_, q) => q,
            Stroke::Arc {
                c,
                r,
                from,
                span,
                convex,
            } => c + DVec2::from_angle(if convex { from + span } else { from }) * r,
        }
    }

    /// Its unit direction where it starts (`at_end` false) or ends.
    pub fn tangent(&self, at_end: bool) -> DVec2 {
        match *self {
            Stroke::Line(p, q) => (q - p).normalize(),
            Stroke::Arc {
                from, span, convex, ..
            } => {
                let a = if convex == at_end { from + span } else { from };
                let t = DVec2::from_angle(a).perp();
                if convex {
                    t
                } else {
                    -t
                }
            }
        }
    }
}

/// The pieces of `f`'s boundary (above) as strokes with the shape on their
/// left, and how far apart two points may be and still be one (10⁻⁹ of
/// the shape's size); `None` for a combination with another leaf than
/// straight polygons and circles, or past [`MAX_PIECES`] pieces.
pub fn strokes(f: &Figure) -> Option<(Vec<Stroke>, f64)> {
    let (all, eps) = read(f)?;
    // Kept where the shape is on one side and not the other.
    let kept = |p: DVec2, n: DVec2| {
        let (out_side, in_side) = (inside(f, p + n * eps), inside(f, p - n * eps));
        (out_side != in_side).then_some(in_side)
    };
    let mut out = Vec::new();
    for (i, &piece) in all.iter().enumerate() {
        match piece {
            SitePiece::Edge(..) => {
                for (p, q, left) in kept_edges(f, &all, i, eps) {
                    out.push(if left {
                        Stroke::Line(p, q)
                    } else {
                        Stroke::Line(q, p)
                    });
                }
            }
            SitePiece::Circle(c, r) => {
                let mut cuts = Vec::new();
                for (j, &other) in all.iter().enumerate() {
                    if j == i {
                        continue;
                    }
                    let hits: Vec<DVec2> = match other {
                        SitePiece::Edge(p, q) => line_circle(p, q, c, r)
                            .into_iter()
                            .filter(|u| (0.0..=1.0).contains(u))
                            .map(|u| p + (q - p) * u)
                            .collect(),
                        SitePiece::Circle(c2, r2) => circle_circle(c, r, c2, r2),
                    };
                    cuts.extend(hits.iter().map(|h| (h.y - c.y).atan2(h.x - c.x)));
                }
                let at = |a: f64| c + DVec2::from_angle(a) * r;
                if cuts.is_empty() {
                    if let Some(convex) = kept(at(0.0), DVec2::X) {
                        out.push(Stroke::Arc {
                            c,
                            r,
                            from: 0.0,
                            span: TAU,
                            convex,
                        });
                    }
                    continue;
                }
                cuts.sort_by(f64::total_cmp);
                for (k, &from) in cuts.iter().enumerate() {
                    let to = if k + 1 < cuts.len() {
                        cuts[k + 1]
                    } else {
                        cuts[0] + TAU
                    };
                    if to <= from {
                        continue;
                    }
                    let mid = (from + to) / 2.0;
                    if let Some(convex) = kept(at(mid), DVec2::from_angle(mid)) {
                        out.push(Stroke::Arc {
                            c,
                            r,
                            from,
                            span: to - from,
                            convex,
                        });
                    }
                }
            }
        }
    }
    // A stretch two pieces share (an edge twice, a circle twice), once.
    let mut once: Vec<Stroke> = Vec::with_capacity(out.len());
    for s in out {
        let same = |o: &Stroke| match (*o, s) {
            (Stroke::Line(..), Stroke::Line(..)) => {
                (o.start() - s.start()).length() <= eps && (o.end() - s.end()).length() <= eps
            }
            (
                Stroke::Arc {
                    c, r, from, span, ..
                },
                Stroke::Arc {
                    c: c2,
                    r: r2,
                    from: f2,
                    span: s2,
                    ..
                },
            ) => (c - c2).length() <= eps && (r - r2).abs() <= eps && from == f2 && span == s2,
            _ => false,
        };
        if !once.iter().any(same) {
            once.push(s);
        }
    }
    Some((once, eps))
}

/// Where the edge a → b (piece i of `all`) crosses the other pieces, and
/// where the ends of an edge along its line (within `eps`) lie, as sorted
/// parameters in [0, 1] with both ends.
fn edge_cuts(i: usize, a: DVec2, b: DVec2, all: &[SitePiece], eps: f64) -> Vec<f64> {
    let d = b - a;
    let mut cuts = vec![0.0, 1.0];
    for (j, &other) in all.iter().enumerate() {
        if j == i {
            continue;
        }
        match other {
            SitePiece::Edge(p, q) => {
                let e = q - p;
                let den = d.perp_dot(e);
                if den.abs() <= 1e-12 * d.length() * e.length() {
                    // Along the same line (within eps): cut where the
                    // other edge's ends lie, so that the stretches two
                    // edges share are the same on both.
                    let off = |x: DVec2| (x - a).perp_dot(d).abs() / d.length();
                    if off(p) <= eps && off(q) <= eps {
                        let l2 = d.length_squared();
                        cuts.push((p - a).dot(d) / l2);
                        cuts.push((q - a).dot(d) / l2);
                    }
                } else {
                    let u = (p - a).perp_dot(e) / den;
                    let v = (p - a).perp_dot(d) / den;
                    if (0.0..=1.0).contains(&v) {
                        cuts.push(u);
                    }
                }
            }
            SitePiece::Circle(c, r) => cuts.extend(line_circle(a, b, c, r)),
        }
    }
    cuts.retain(|u| (0.0..=1.0).contains(u));
    cuts.sort_by(f64::total_cmp);
    cuts
}

/// The stretches of edge piece i (none for a circle) that lie on the
/// boundary of `f` — the shape on one side and not the other, tested `eps`
/// off each stretch's middle — as (start, end, whether the shape is on
/// the left).
fn kept_edges(f: &Figure, all: &[SitePiece], i: usize, eps: f64) -> Vec<(DVec2, DVec2, bool)> {
    let SitePiece::Edge(a, b) = all[i] else {
        return Vec::new();
    };
    let d = b - a;
    if d == DVec2::ZERO {
        return Vec::new();
    }
    let normal = d.perp().normalize();
    let cuts = edge_cuts(i, a, b, all, eps);
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        if w[1] > w[0] {
            let mid = a + d * ((w[0] + w[1]) / 2.0);
            let (left, right) = (inside(f, mid + normal * eps), inside(f, mid - normal * eps));
            if left != right {
                out.push((a + d * w[0], a + d * w[1], left));
            }
        }
    }
    out
}

/// The pieces of `f`'s leaves, and how far off a piece its sides are
/// tested (10⁻⁹ of the largest coordinate, a circle's reach); `None` for
/// another leaf or past [`MAX_PIECES`].
fn read(f: &Figure) -> Option<(Vec<SitePiece>, f64)> {
    let mut all = Vec::new();
    if !pieces(f, &mut all) || all.len() > MAX_PIECES {
        return None;
    }
    let size = all.iter().fold(0.0f64, |s, p| match *p {
        SitePiece::Edge(a, b) => s.max(a.abs().max_element()).max(b.abs().max_element()),
        SitePiece::Circle(c, r) => s.max(c.abs().max_element() + r),
    });
    Some((all, 1e-9 * size))
}

/// A combination of straight polygons as the loops of its boundary, each
/// with the shape on its left: the kept pieces of `boundary`'s rule,
/// chained end to start (ends within 10⁻⁹ of the shape's size are one
/// point), and runs along one line merged. `None` for a combination with a
/// circle or another leaf, past [`MAX_PIECES`] edges, or whose pieces do
/// not close into loops — or touch, where a corner could be chained two
/// ways (see [`touching_outline`]).
pub fn outline(f: &Figure) -> Option<crate::plane::Outlines> {
    chained(f, false)
}

/// [`outline`], but where the boundary touches itself the loops through
/// that point are chained the first way found: each is closed, and they
/// still make the whole boundary, each edge once (what a sum takes of it),
/// though not necessarily as simple loops.
pub fn touching_outline(f: &Figure) -> Option<crate::plane::Outlines> {
    chained(f, true)
}

fn chained(f: &Figure, touching: bool) -> Option<crate::plane::Outlines> {
    let (all, tol) = read(f)?;
    if all.iter().any(|p| matches!(p, SitePiece::Circle(..))) {
        return None;
    }
    let mut segs: Vec<(DVec2, DVec2)> = Vec::new();
    for i in 0..all.len() {
        for (p, q, left) in kept_edges(f, &all, i, tol) {
            if (q - p).length() > tol {
                segs.push(if left { (p, q) } else { (q, p) });
            }
        }
    }
    // Chained: each segment's end to the start of the one that follows it
    // (one only, or the boundary touches itself and is left to the caller).
    let mut used = vec![false; segs.len()];
    let mut loops = Vec::new();
    for first in 0..segs.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut pts = vec![segs[first].0];
        let mut end = segs[first].1;
        loop {
            if (end - pts[0]).length() <= tol {
                break;
            }
            let next: Vec<usize> = (0..segs.len())
                .filter(|&k| !used[k] && (segs[k].0 - end).length() <= tol)
                .collect();
            let k = match next[..] {
                [k] => k,
                [k, ..] if touching => k,
                _ => return None,
            };
            used[k] = true;
            pts.push(segs[k].0);
            end = segs[k].1;
        }
        // Points where the boundary runs straight on are not corners.
        let n = pts.len();
        let corners: Vec<DVec2> = (0..n)
            .filter(|&k| {
                let (a, b, c) = (pts[(k + n - 1) % n], pts[k], pts[(k + 1) % n]);
                (b - a).perp_dot(c - b).abs() > tol * (b - a).length().max((c - b).length())
                    || (b - a).dot(c - b) < 0.0
            })
            .map(|k| pts[k])
            .collect();
        let dropped = !loops.is_empty() && crate::mutant::active("outline_first_loop_only");
        if corners.len() >= 3 && !dropped {
            loops.push(corners);
        }
    }
    (!loops.is_empty()).then(|| crate::plane::Outlines::polygons(loops))
}

/// The points where two circles cross (none, or two).
fn circle_circle(c1: DVec2, r1: f64, c2: DVec2, r2: f64) -> Vec<DVec2> {
    let d = c2 - c1;
    let l = d.length();
    if l == 0.0 || l > r1 + r2 || l < (r1 - r2).abs() {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + l * l) / (2.0 * l);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let m = c1 + d * (a / l);
    let p = d.perp() * (h / l);
    vec![m + p, m - p]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::Outlines;

    fn square(lo: DVec2, hi: DVec2) -> Figure {
        Figure::Polygon(Outlines::polygons(vec![vec![
            lo,
            DVec2::new(hi.x, lo.y),
            hi,
            DVec2::new(lo.x, hi.y),
        ]]))
    }

    /// A quarter disc: its corner, the two ends of its arc, and the arc of
    /// normals from 0 to 90°.
    #[test]
    fn quarter_disc() {
        let f = Figure::Op(
            Op::Intersection,
            vec![
                Figure::disc(DVec2::ZERO, 2.0),
                square(DVec2::ZERO, DVec2::splat(3.0)),
            ],
        );
        let mut out = Vec::new();
        assert!(sites(&f, &mut out));
        let arcs: Vec<_> = out.iter().filter_map(|s| s.arc).collect();
        assert_eq!(arcs.len(), 1);
        let (from, span) = arcs[0];
        assert!(
            from.abs() < 1e-12 && (span - TAU / 4.0).abs() < 1e-12,
            "{arcs:?}"
        );
        for p in [DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(0.0, 2.0)] {
            assert!(
                out.iter().any(|s| s.r == 0.0 && (s.c - p).length() < 1e-12),
                "{p}"
            );
        }
        // Nothing outside the quarter disc.
        assert!(out
            .iter()
            .all(|s| s.r > 0.0 || s.c.min_element() > -1e-12 && s.c.length() < 2.0 + 1e-12));
    }

    /// A square less its left half (the edges meet exactly): the right
    /// half's corners only.
    #[test]
    fn difference_on_shared_edges() {
        let f = Figure::Op(
            Op::Difference,
            vec![
                square(DVec2::ZERO, DVec2::splat(2.0)),
                square(DVec2::ZERO, DVec2::new(1.0, 2.0)),
            ],
        );
        let mut out = Vec::new();
        assert!(sites(&f, &mut out));
        assert!(
            out.iter().all(|s| s.r == 0.0 && s.c.x >= 1.0 - 1e-12),
            "{out:?}"
        );
        assert!(out.iter().any(|s| s.c == DVec2::new(1.0, 0.0)));
        assert!(out.iter().any(|s| s.c == DVec2::new(2.0, 2.0)));
    }

    /// A frame (a square less a square inside it): two loops, the outer
    /// counter-clockwise and the hole clockwise (the shape on the left of
    /// each), four corners each.
    #[test]
    fn frame_outline() {
        let f = Figure::Op(
            Op::Difference,
            vec![
                square(DVec2::ZERO, DVec2::splat(4.0)),
                square(DVec2::ONE, DVec2::splat(3.0)),
            ],
        );
        let o = outline(&f).expect("two loops");
        assert_eq!(o.loops.len(), 2);
        let area = |l: &Vec<DVec2>| {
            (0..l.len())
                .map(|i| l[i].perp_dot(l[(i + 1) % l.len()]))
                .sum::<f64>()
                / 2.0
        };
        let mut areas: Vec<f64> = o.loops.iter().map(area).collect();
        areas.sort_by(f64::total_cmp);
        assert_eq!(areas, vec![-4.0, 16.0]);
        assert!(o.loops.iter().all(|l| l.len() == 4));
    }

    /// Two squares that overlap: one loop of 8 corners around their union,
    /// where their edges cross; with a circle, none (not straight).
    #[test]
    fn union_outline() {
        let two = vec![
            square(DVec2::ZERO, DVec2::splat(2.0)),
            square(DVec2::ONE, DVec2::splat(3.0)),
        ];
        let o = outline(&Figure::Op(Op::Union, two.clone())).expect("one loop");
        assert_eq!(o.loops.len(), 1);
        assert_eq!(o.loops[0].len(), 8);
        assert!(o.loops[0].contains(&DVec2::new(2.0, 1.0)));
        let mut with_disc = two;
        with_disc.push(Figure::disc(DVec2::ZERO, 1.0));
        assert!(outline(&Figure::Op(Op::Union, with_disc)).is_none());
    }

    /// A disc with a hole: the hole's circle is concave, not a site.
    #[test]
    fn ring() {
        let f = Figure::Op(
            Op::Difference,
            vec![
                Figure::disc(DVec2::ZERO, 2.0),
                Figure::disc(DVec2::ZERO, 1.0),
            ],
        );
        let mut out = Vec::new();
        assert!(sites(&f, &mut out));
        assert_eq!(out, vec![Site::disc(DVec2::ZERO, 2.0)]);
    }
}
