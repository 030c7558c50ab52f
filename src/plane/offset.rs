//! OpenSCAD's `offset(r | delta, chamfer)`, exactly, as a CSG of 2-D
//! leaves csgrt already renders exactly.
//!
//! OpenSCAD 2021.01 offsets the union of the children with Clipper: `r`
//! rounds the corners (the Minkowski sum with the disc of radius r, or for
//! r < 0 the erosion by it), `delta` keeps them sharp (a miter, Clipper's
//! limit 10⁶ being no limit), `chamfer = true` cuts them square at distance
//! delta from the corner, across its bisector (Clipper's `jtSquare`). For a
//! simple region R with edges e (outward normals n) and corners v:
//!
//! - growing by d > 0: R ∪ ⋃ band(e) ∪ ⋃ join(v), band(e) the rectangle
//!   the edge sweeps moving out to distance d, join(v) at each convex corner
//!   the disc of radius d about v (round), the kite v, v + d·n₁, the miter
//!   point v + d·(n₁ + n₂)/(1 + n₁·n₂), v + d·n₂ (miter), or that kite cut
//!   at distance d from v (chamfer); a reflex corner needs none, its two
//!   bands overlapping there;
//! - shrinking by d < 0: R − ⋃ band′(e) − ⋃ join′(v), the bands swept
//!   inward and the joins at the reflex corners (the convex ones of the
//!   outside, which the same rules grow).
//!
//! Growing distributes over union ((A ∪ B) ⊕ D = (A ⊕ D) ∪ (B ⊕ D): a
//! union's convex corners are its operands', and where their edges cross
//! the union is reflex), shrinking over intersection and over a union of
//! shapes whose boxes are apart (the glyphs of a text, mostly); a circle
//! grows to the circle of radius R + d. Curved outlines offset as one leaf
//! of their own ([`crate::plane::round_offset`]). What needs the boundary of a
//! combination — shrinking a union whose parts' boxes meet, growing an
//! intersection, either of a difference — is done on the loops of its
//! boundary when it is made of straight polygons
//! ([`super::sites::outline`]), and with circles too through the strokes
//! of its boundary swept by the disc (`around`); ellipses and
//! self-crossing polygons, not yet.

use super::figure::{is_circle, Figure};
use super::round_offset::{offsettable, RoundOffset};
use super::sites::{bounds, clip, Site, Stroke};
use super::{Outlines, Region};
use crate::math::boolean::Op;
use glam::{DAffine2, DVec2};
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

/// How corners are joined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Join {
    Round,
    Miter,
    Square,
}

/// Clipper's miter test: a corner whose normals are this close to opposite
/// (1 + n₁·n₂ below it) is squared instead (OpenSCAD's miter limit of 10⁶:
/// 2/limit²).
const MITER_LIMIT: f64 = 2e-12;

/// The most edges an outline to offset may have (the self-crossing test
/// compares every pair).
pub const MAX_OFFSET_EDGES: usize = 20_000;

/// `f` offset by `d`, or why it cannot be yet.
pub fn offset(f: Figure, join: Join, d: f64) -> Result<Option<Figure>, String> {
    if d == 0.0 {
        return Ok(Some(f));
    }
    match f {
        Figure::Op(Op::Union, kids) if d > 0.0 => {
            let mut out = Vec::new();
            for k in kids {
                out.extend(offset(k, join, d)?);
            }
            Ok(union(out))
        }
        // Shrinking a union of shapes whose boxes are apart: a disc inside
        // a union of disjoint closed sets lies in one of them (it is
        // connected), so the union's erosion is the union of theirs — and
        // Clipper too offsets each outline by itself.
        Figure::Op(Op::Union, kids) if d < 0.0 && boxes_apart(&kids) => {
            let mut out = Vec::new();
            for k in kids {
                out.extend(offset(k, join, d)?);
            }
            Ok(union(out))
        }
        Figure::Op(Op::Intersection, kids) if d < 0.0 => {
            let mut out = Vec::new();
            for k in kids {
                match offset(k, join, d)? {
                    Some(x) => out.push(x),
                    None => return Ok(None),
                }
            }
            Ok(Some(Figure::Op(Op::Intersection, out)))
        }
        // Any other combination of straight polygons: the loops of its
        // boundary, offset as one polygon.
        // (Loops that touch each other — holes meeting at a corner — are
        // offset through the strokes, whose corners are paired by wedge.)
        ref combination @ Figure::Op(op, _) => match super::sites::outline(combination) {
            Some(o) if !self_crossing(&o) => polygon(o, join, d),
            _ => match super::sites::strokes(combination) {
                Some((strokes, tol)) => around(combination.clone(), &strokes, tol, join, d),
                _ if super::sites::too_many_pieces(combination) => Err(format!(
                    "offsetting a combination of more than {} edges and circles (csgrt's limit)",
                    super::sites::MAX_PIECES
                )),
                // (Its curves, ellipses, hulls or projections are flattened
                // by the resolver and offset again: this is not said.)
                _ => Err(format!(
                    "{} a 2-D {} of curves, ellipses, hulls or projections has no exact form",
                    if d > 0.0 { "growing" } else { "shrinking" },
                    match op {
                        Op::Union => "union",
                        Op::Intersection => "intersection",
                        Op::Difference => "difference",
                        Op::Xor => "drawing",
                    }
                )),
            },
        },
        Figure::Ellipse(e) => {
            if !is_circle(e.matrix2) {
                return Err("an ellipse's offset has no exact form".into());
            }
            let r2 = e.matrix2.x_axis.length() + d;
            Ok((r2 > 0.0).then(|| Figure::disc(e.translation, r2)))
        }
        Figure::Polygon(o) => polygon(o, join, d),
        Figure::Section(..) => Err("a projection's offset has no exact form".into()),
        Figure::Hull(_) => Err("a 2-D hull's offset has no exact form".into()),
        Figure::Offset(..) => {
            Err("an offset of an offset of curved outlines has no exact form".into())
        }
    }
}

/// Whether no two of `kids` have boxes that meet (each box holds its
/// shape: [`Figure::range`] is exact for leaves and never smaller for
/// combinations). Sorted by their left sides and swept.
fn boxes_apart(kids: &[Figure]) -> bool {
    let mut boxes: Vec<(DVec2, DVec2)> = kids
        .iter()
        .map(|k| {
            let ((x0, x1), (y0, y1)) = (k.range(DVec2::X), k.range(DVec2::Y));
            (DVec2::new(x0, y0), DVec2::new(x1, y1))
        })
        .collect();
    if boxes
        .iter()
        .any(|(lo, hi)| !(lo.is_finite() && hi.is_finite()))
    {
        return false;
    }
    boxes.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            if b.0.x > a.1.x {
                break;
            }
            if b.0.y <= a.1.y && a.0.y <= b.1.y {
                return false;
            }
        }
    }
    true
}

fn union(mut parts: Vec<Figure>) -> Option<Figure> {
    match parts.len() {
        0 => None,
        1 => parts.pop(),
        _ => Some(Figure::Op(Op::Union, parts)),
    }
}

/// A simple polygon region grown or shrunk.
fn polygon(o: Outlines, join: Join, d: f64) -> Result<Option<Figure>, String> {
    polygon_arcs(o, join, d, None)
}

/// Straight outlines `o` grown by `d` > 0 with round joins, each corner's
/// disc cut to the sector its offset takes of it (the points whose nearest
/// point of the outline is that corner lie between its edges' normals) and
/// flattened to its chords within `eps`: the offset's convex pieces as few
/// and as small as they can be (a flattened curve's every corner is one,
/// its sector a sliver); other outlines and distances as [`offset`] makes
/// them.
pub fn grown_flat(o: Outlines, d: f64, eps: f64) -> Result<Option<Figure>, String> {
    if d > 0.0 && !o.curved() {
        polygon_arcs(o, Join::Round, d, Some(eps))
    } else {
        offset(Figure::Polygon(o), Join::Round, d)
    }
}

/// [`polygon`], growing corners flattened as [`grown_flat`] says where
/// `arcs` gives the error.
fn polygon_arcs(
    o: Outlines,
    join: Join,
    d: f64,
    arcs: Option<f64>,
) -> Result<Option<Figure>, String> {
    if o.curved() {
        return curved(o, join, d);
    }
    // A point repeated (OpenSCAD's points often are) makes an edge of no
    // length, which bounds nothing: left out, and so is a loop left with
    // fewer than 3 points (unless none is left).
    let loops: Vec<Vec<DVec2>> = o
        .loops
        .iter()
        .map(|l| {
            (0..l.len())
                .filter(|&i| l[i] != l[(i + 1) % l.len()])
                .map(|i| l[i])
                .collect::<Vec<DVec2>>()
        })
        .filter(|l| l.len() >= 3)
        .collect();
    let o = if loops.is_empty() {
        o
    } else {
        Outlines::polygons(loops)
    };
    let edges = o.loops.iter().map(|l| l.len()).sum::<usize>();
    if edges > MAX_OFFSET_EDGES {
        return Err(format!(
            "offsetting an outline of more than {MAX_OFFSET_EDGES} edges (csgrt's limit)"
        ));
    }
    if self_crossing(&o) {
        // Its region's boundary (cut where it crosses or touches itself),
        // stroked, as a combination's.
        let f = Figure::Polygon(o);
        return match super::sites::strokes(&f) {
            Some((mut strokes, tol)) => {
                // The fault: half the boundary stroked.
                if crate::mutant::active("crossing_half_stroked") {
                    strokes.truncate(strokes.len() / 2);
                }
                around(f, &strokes, tol, join, d)
            }
            None => Err(format!(
                "offsetting an outline of more than {} edges that crosses or touches itself",
                super::sites::MAX_PIECES
            )),
        };
    }
    let region = Region::new(o);
    // Outward (d > 0) or inward (d < 0) by |d|.
    let k = d.abs();
    let side = d.signum();
    let mut parts = Vec::new();
    let mut start = 0;
    for l in &region.outlines.loops {
        let m = l.len();
        for i in 0..m {
            let (e1, e2) = (start + (i + m - 1) % m, start + i);
            let (a, v) = region.edges[e1];
            let b = region.edges[e2].1;
            let (n1, n2) = (region.normals[e1] * side, region.normals[e2] * side);
            // The band swept by the edge from v to b.
            parts.push(Figure::Polygon(Outlines::polygons(vec![vec![
                v,
                b,
                b + n2 * k,
                v + n2 * k,
            ]])));
            // A corner the offset side sees as convex: the next edge turns
            // away from n₁.
            if (b - v).dot(n1) >= 0.0 || (v - a).perp_dot(b - v) == 0.0 {
                continue;
            }
            let (t1, t2) = ((v - a).normalize(), (b - v).normalize());
            parts.push(match arcs {
                Some(eps) if d > 0.0 => sector(v, n1, n2, k, eps),
                _ => join_piece(join, v, n1, n2, t1, t2, k),
            });
        }
        start += m;
    }
    let body = Figure::Polygon(region.outlines.clone());
    Ok(Some(if d > 0.0 {
        parts.insert(0, body);
        Figure::Op(Op::Union, parts)
    } else {
        parts.insert(0, body);
        Figure::Op(Op::Difference, parts)
    }))
}

/// A combination of polygons and circles offset by `d` through the strokes
/// of its boundary (shape on their left; ends within `tol` are one point):
/// R ⊕ D = R ∪ (∂R ⊕ D) and R ⊖ D = R − (∂R ⊕ D), and the disc's sweep
/// along a stroke is the band of the stroke's points within |d| of it — a
/// rectangle across a line, the annular sector of radii r ∓ |d| over an
/// arc's angles ([`annular`]) — with a disc about each end (the points
/// nearest an end, which the sweep misses). With miter and square joins,
/// the kites of the corners the offset side sees as convex are joined on
/// (grown) or taken away too (shrunk), as for a curved outline: the round
/// offset lies in the sharp one, and the kites hold the rest.
fn around(
    body: Figure,
    strokes: &[Stroke],
    tol: f64,
    join: Join,
    d: f64,
) -> Result<Option<Figure>, String> {
    let (k, side) = (d.abs(), d.signum());
    let mut parts = vec![body];
    let mut ends: Vec<DVec2> = Vec::new();
    for s in strokes {
        match *s {
            Stroke::Line(p, q) => {
                let n = (q - p).perp().normalize() * k;
                parts.push(Figure::Polygon(Outlines::polygons(vec![vec![
                    p - n,
                    q - n,
                    q + n,
                    p + n,
                ]])));
            }
            Stroke::Arc {
                c, r, from, span, ..
            } => {
                if !crate::mutant::active("offset_arcs_unswept") {
                    parts.extend(annular(c, r - k, r + k, from, span));
                }
                if span >= TAU {
                    continue;
                }
            }
        }
        for e in [s.start(), s.end()] {
            if ends.iter().all(|x| (*x - e).length() > tol) {
                ends.push(e);
            }
        }
    }
    parts.extend(ends.iter().map(|&e| Figure::disc(e, k)));
    if join != Join::Round {
        // The corners: where one stroke ends and the next starts. Whole
        // circles have none; strokes no longer than `slack` = 1000 tol
        // (slivers of an arc cut twice where a band's edge meets its
        // circle tangent: numerical noise) are passed over (copies are
        // not there: strokes() keeps a shared stretch once), and a
        // stroke's next is the one that starts nearest its end, within
        // `slack`; two within `tol` are a boundary that touches itself.
        let slack = 1e3 * tol;
        let chain: Vec<&Stroke> = strokes
            .iter()
            .filter(|s| {
                let whole = matches!(s, Stroke::Arc { span, .. } if *span >= TAU);
                !whole && (s.end() - s.start()).length() > slack
            })
            .collect();
        for s in &chain {
            let v = s.end();
            let mut next: Vec<(f64, &Stroke)> = chain
                .iter()
                .map(|n| ((n.start() - v).length(), *n))
                .filter(|(l, _)| *l <= slack)
                .collect();
            next.sort_by(|x, y| x.0.total_cmp(&y.0));
            // Those starting within `tol` along one direction overlap (a
            // stretch two pieces share, cut a little differently): any
            // one serves.
            let t = next.first().map(|(_, n)| n.tangent(false));
            let close = next.iter().filter(|(l, _)| *l <= tol);
            let one_way = close
                .clone()
                .all(|(_, n)| t.is_some_and(|t| (n.tangent(false) - t).length() <= 1e-9));
            // Where the boundary touches itself (two strokes start at v
            // along different ways), the stroke that bounds the same wedge
            // of the offset side as s, whose corners get the joins: grown,
            // the wedge of the shape (on the strokes' left), the first
            // stroke met turning clockwise from the way back along s;
            // shrunk, the wedge of the outside (on their right), the first
            // met turning counter-clockwise — as Clipper offsets each loop
            // of holes that meet at a corner with its own join there.
            let back = -s.tangent(true);
            let clockwise = |n: &Stroke| {
                let t = n.tangent(false);
                let a = side * t.perp_dot(back).atan2(t.dot(back));
                if a <= 0.0 {
                    a + TAU
                } else {
                    a
                }
            };
            let n = match next[..] {
                [] => continue,
                [(_, n)] => n,
                [(_, n), (l, _), ..] if l > tol || one_way => n,
                _ => {
                    let wedge = close.map(|(_, n)| *n).min_by(|a, b| {
                        if crate::mutant::active("offset_wedge_widest") {
                            clockwise(b).total_cmp(&clockwise(a))
                        } else {
                            clockwise(a).total_cmp(&clockwise(b))
                        }
                    });
                    wedge.expect("two strokes start at v")
                }
            };
            let (t1, t2) = (s.tangent(true), n.tangent(false));
            // Offset-side normals: the outside is on a stroke's right.
            let (n1, n2) = (-t1.perp() * side, -t2.perp() * side);
            if t2.dot(n1) >= 0.0 || 1.0 - n1.dot(n2) <= 1e-12 {
                continue;
            }
            parts.push(join_piece(join, v, n1, n2, t1, t2, k));
        }
    }
    let op = if d > 0.0 { Op::Union } else { Op::Difference };
    Ok(Some(Figure::Op(op, parts)))
}

/// The annular sector about c between radii `inner` (none below 0) and
/// `outer` over the angles from `from` to `from + span`: the ring for a
/// whole turn, else a sector of at most a half turn at a time, each the
/// disc met with the polygon of its wedge cut to the sector's own box (so
/// that it frames exactly), less the inner disc.
fn annular(c: DVec2, inner: f64, outer: f64, from: f64, span: f64) -> Vec<Figure> {
    let less_inner = |f: Figure| {
        if inner > 0.0 {
            Figure::Op(Op::Difference, vec![f, Figure::disc(c, inner)])
        } else {
            f
        }
    };
    if span >= TAU {
        return vec![less_inner(Figure::disc(c, outer))];
    }
    let m = (span / PI).ceil().max(1.0) as usize;
    let step = span / m as f64;
    let at = |a: f64, r: f64| c + DVec2::from_angle(a) * r;
    (0..m)
        .map(|i| {
            let a0 = from + step * i as f64;
            let a1 = a0 + step;
            // The sector's box: its outer arc's ends and axis points, and
            // its inner arc's ends (the centre when it has no hole).
            let arc = Site {
                c,
                r: outer,
                arc: Some((a0, step)),
            };
            let mut pts = arc.extremes();
            if inner > 0.0 {
                pts.extend([at(a0, inner), at(a1, inner)]);
            } else {
                pts.push(c);
            }
            let (lo, hi) = bounds(&pts);
            // The wedge: rays at a0 and a1 through points 2·outer out,
            // joined through the middle ray (each chord at least √2·outer
            // from c, a step being at most a half turn).
            let far = 2.0 * outer;
            let mut wedge = vec![c, at(a0, far), at((a0 + a1) / 2.0, far), at(a1, far)];
            for (axis, bound, sign) in [
                (DVec2::X, lo.x, 1.0),
                (DVec2::X, hi.x, -1.0),
                (DVec2::Y, lo.y, 1.0),
                (DVec2::Y, hi.y, -1.0),
            ] {
                wedge = clip(&wedge, |p| (p.dot(axis) - bound) * sign);
            }
            let sector = Figure::Op(
                Op::Intersection,
                vec![
                    Figure::disc(c, outer),
                    Figure::Polygon(Outlines::polygons(vec![wedge])),
                ],
            );
            less_inner(sector)
        })
        .collect()
}

/// The join at corner v between an edge arriving along unit tangent t1
/// and one leaving along t2, their offset-side unit normals n1 and n2, at
/// distance k: a disc (round), the kite to the offset edges' meeting point
/// (miter), or that kite cut across the bisector at distance k (square,
/// and a miter beyond Clipper's limit).
fn join_piece(join: Join, v: DVec2, n1: DVec2, n2: DVec2, t1: DVec2, t2: DVec2, k: f64) -> Figure {
    let cos = n1.dot(n2);
    match join {
        Join::Round => Figure::disc(v, k),
        Join::Miter
            if 1.0 + cos >= MITER_LIMIT && !crate::mutant::active("offset_miter_squared") =>
        {
            let miter = v + (n1 + n2) * (k / (1.0 + cos));
            Figure::Polygon(Outlines::polygons(vec![vec![
                v,
                v + n1 * k,
                miter,
                v + n2 * k,
            ]]))
        }
        _ => {
            // Cut across the bisector at distance k from v: each offset
            // edge runs on by k·tan(θ/4) past its end.
            let theta = n1.perp_dot(n2).abs().atan2(cos);
            let run = k * (theta / 4.0).tan();
            Figure::Polygon(Outlines::polygons(vec![vec![
                v,
                v + n1 * k,
                v + n1 * k + t1 * run,
                v + n2 * k - t2 * run,
                v + n2 * k,
            ]]))
        }
    }
}

/// The sector of the disc of radius `k` about `v` from normal `n1` to `n2`
/// (less than a half turn apart) as a polygon: `v` and the arc's points at
/// equal angles, the fewest whose chords stray at most `eps` from it.
fn sector(v: DVec2, n1: DVec2, n2: DVec2, k: f64, eps: f64) -> Figure {
    let theta = n1.perp_dot(n2).atan2(n1.dot(n2));
    // A chord over angle a strays k·(1 − cos(a/2)) from its arc.
    let step = 2.0 * (1.0 - (eps / k).min(1.0)).acos();
    let n = if step > 0.0 {
        ((theta.abs() / step).ceil() as usize).clamp(1, super::flat::MAX_CHORDS)
    } else {
        super::flat::MAX_CHORDS
    };
    let mut pts = vec![v];
    pts.extend((0..=n).map(|i| v + DVec2::from_angle(theta * i as f64 / n as f64).rotate(n1) * k));
    Figure::Polygon(Outlines::polygons(vec![pts]))
}

/// Outlines with curved (quadratic) edges offset: with round joins the
/// region of points within |d| of R (grown) or of R farther than |d| from
/// its outline (shrunk), one leaf ([`crate::plane::round_offset`]); with miter or
/// square joins that leaf joined with the kites at its sharp corners the
/// offset side sees as convex (grown: R ⊕ D ⊆ the mitered offset, and the
/// kites hold the rest), or less the kites at the corners the outside sees
/// as convex (shrunk). A corner whose edges meet tangent needs none: its
/// kite would lie in the disc about it.
fn curved(o: Outlines, join: Join, d: f64) -> Result<Option<Figure>, String> {
    if !o.ctrl.iter().flatten().all(|c| offsettable(*c)) {
        return Err("cubic curves (SVG drawings, CFF fonts) have no exact offset here".into());
    }
    let edges = o.loops.iter().map(|l| l.len()).sum::<usize>();
    if edges > MAX_OFFSET_EDGES {
        return Err(format!(
            "offsetting an outline of more than {MAX_OFFSET_EDGES} edges (csgrt's limit)"
        ));
    }
    let region = Region::new(o);
    let (k, side) = (d.abs(), d.signum());
    let mut kites = Vec::new();
    if join != Join::Round {
        let mut start = 0;
        for l in &region.outlines.loops {
            let m = l.len();
            for i in 0..m {
                let (e1, e2) = (start + (i + m - 1) % m, start + i);
                let v = region.edges[e2].0;
                let (t1, t2) = (end_tangent(&region, e1), start_tangent(&region, e2));
                let (Some(t1), Some(t2)) = (t1.try_normalize(), t2.try_normalize()) else {
                    continue;
                };
                let (n1, n2) = (
                    region.normal_at(e1, v) * side,
                    region.normal_at(e2, v) * side,
                );
                // Convex as the offset side sees it, and not tangent (the
                // miter point within rounding of the disc).
                if t2.dot(n1) >= 0.0 || 1.0 - n1.dot(n2) <= 1e-12 {
                    continue;
                }
                kites.push(join_piece(join, v, n1, n2, t1, t2, k));
            }
            start += m;
        }
    }
    let leaf = Figure::Offset(Arc::new(RoundOffset::new(region, d)), DAffine2::IDENTITY);
    if kites.is_empty() {
        return Ok(Some(leaf));
    }
    kites.insert(0, leaf);
    let op = if d > 0.0 { Op::Union } else { Op::Difference };
    Ok(Some(Figure::Op(op, kites)))
}

/// Edge e's direction where it leaves its start (its first control point
/// apart from the start, else its end).
fn start_tangent(r: &Region, e: usize) -> DVec2 {
    let (a, b) = r.edges[e];
    r.ctrl[e]
        .points()
        .chain(std::iter::once(b))
        .find(|&p| p != a)
        .unwrap_or(b)
        - a
}

/// Edge e's direction where it arrives at its end.
fn end_tangent(r: &Region, e: usize) -> DVec2 {
    let (a, b) = r.edges[e];
    let pts: Vec<DVec2> = std::iter::once(a).chain(r.ctrl[e].points()).collect();
    b - pts.into_iter().rev().find(|&p| p != b).unwrap_or(a)
}

/// Whether two edges of the outlines meet other than where consecutive
/// edges of a loop share their end.
fn self_crossing(o: &Outlines) -> bool {
    let edges: Vec<(DVec2, DVec2, usize, usize)> = o
        .loops
        .iter()
        .enumerate()
        .flat_map(|(j, l)| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()], j, i)))
        .collect();
    let orient = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let on = |a: DVec2, b: DVec2, p: DVec2| {
        orient(a, b, p) == 0.0 && p.cmpge(a.min(b)).all() && p.cmple(a.max(b)).all()
    };
    for (x, &(a, b, ja, ia)) in edges.iter().enumerate() {
        let (lo, hi) = (a.min(b), a.max(b));
        for &(c, d, jc, ic) in &edges[x + 1..] {
            if c.max(d).cmplt(lo).any() || c.min(d).cmpgt(hi).any() {
                continue;
            }
            let len = o.loops[ja].len();
            let adjacent = ja == jc && (ic == (ia + 1) % len || ia == (ic + 1) % len);
            if adjacent {
                // Sharing one end p: they meet again only folding back,
                // the far end of one on the other.
                let (p, far1, far2) = if ic == (ia + 1) % len {
                    (b, a, d)
                } else {
                    (a, b, c)
                };
                if on(c, d, far1) && far1 != p || on(a, b, far2) && far2 != p {
                    return true;
                }
                continue;
            }
            let (d1, d2) = (orient(a, b, c), orient(a, b, d));
            let (d3, d4) = (orient(c, d, a), orient(c, d, b));
            if (d1 > 0.0) != (d2 > 0.0)
                && (d1 < 0.0) != (d2 < 0.0)
                && (d3 > 0.0) != (d4 > 0.0)
                && (d3 < 0.0) != (d4 < 0.0)
            {
                return true;
            }
            if on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b) {
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sq(c: DVec2, h: f64) -> Vec<DVec2> {
        vec![
            c + DVec2::new(-h, -h),
            c + DVec2::new(h, -h),
            c + DVec2::new(h, h),
            c + DVec2::new(-h, h),
        ]
    }

    #[test]
    fn self_crossing_outlines_are_found() {
        let z = DVec2::ZERO;
        assert!(!self_crossing(&Outlines::polygons(vec![
            sq(z, 2.0),
            sq(z, 1.0)
        ])));
        let bow = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
        ];
        assert!(self_crossing(&Outlines::polygons(vec![bow])));
        // Two squares touching at a corner.
        let touching = vec![sq(z, 1.0), sq(DVec2::new(2.0, 2.0), 1.0)];
        assert!(self_crossing(&Outlines::polygons(touching)));
        // A spike folding back along itself.
        let fold = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
        ];
        assert!(self_crossing(&Outlines::polygons(vec![fold])));
    }

    /// Round offsets of combinations with circles against the definition:
    /// grown, the points of R or within |d| of its boundary; shrunk, the
    /// points of R at least |d| from it. The boundary is sampled from the
    /// leaves' own outlines (every 10⁻⁴ of a turn or an edge) where R is on
    /// one side only; points within 10⁻³ of the offset's edge are skipped.
    #[test]
    fn round_offsets_of_combinations_with_circles() {
        use super::super::sites::inside;
        let z = DVec2::ZERO;
        let square = |c: DVec2, h: f64| Figure::Polygon(Outlines::polygons(vec![sq(c, h)]));
        let cases = [
            Figure::Op(
                Op::Difference,
                vec![Figure::disc(z, 2.0), Figure::disc(z, 1.0)],
            ),
            Figure::Op(
                Op::Difference,
                vec![Figure::disc(z, 2.0), square(DVec2::ONE, 1.0)],
            ),
            Figure::Op(
                Op::Union,
                vec![Figure::disc(z, 1.5), square(DVec2::ONE, 1.0)],
            ),
            Figure::Op(
                Op::Intersection,
                vec![Figure::disc(z, 2.0), square(DVec2::new(1.0, 0.0), 1.5)],
            ),
        ];
        let mut rand = crate::plane::tests::uniform(1);
        for x in &cases {
            let mut edge: Vec<DVec2> = Vec::new();
            let mut leaves = vec![x];
            while let Some(f) = leaves.pop() {
                match f {
                    Figure::Op(_, kids) => leaves.extend(kids),
                    Figure::Ellipse(e) => edge.extend(
                        (0..10_000)
                            .map(|i| e.transform_point2(DVec2::from_angle(i as f64 * TAU / 1e4))),
                    ),
                    Figure::Polygon(o) => {
                        for l in &o.loops {
                            for (i, &a) in l.iter().enumerate() {
                                let b = l[(i + 1) % l.len()];
                                edge.extend((0..10_000).map(|k| a + (b - a) * (k as f64 / 1e4)));
                            }
                        }
                    }
                    _ => unreachable!(),
                }
            }
            let probe = |p: DVec2| {
                [DVec2::X, DVec2::Y, DVec2::ONE.normalize()]
                    .iter()
                    .any(|&n| inside(x, p + n * 1e-7) != inside(x, p - n * 1e-7))
            };
            edge.retain(|&p| probe(p));
            for d in [0.5, -0.3] {
                let off = offset(x.clone(), Join::Round, d).unwrap().unwrap();
                for _ in 0..400 {
                    let p = DVec2::new(rand() * 6.0 - 3.0, rand() * 6.0 - 3.0);
                    let dist = edge
                        .iter()
                        .map(|&q| (q - p).length())
                        .fold(f64::INFINITY, f64::min);
                    if (dist - d.abs()).abs() < 1e-3 {
                        continue;
                    }
                    let want = if d > 0.0 {
                        inside(x, p) || dist <= d
                    } else {
                        inside(x, p) && dist >= -d
                    };
                    assert_eq!(inside(&off, p), want, "{x:?} offset by {d} at {p}");
                }
            }
        }
    }

    /// Past the limit of pieces a combination's boundary is read from,
    /// the offset says so.
    #[test]
    fn the_limit_of_pieces_is_named() {
        let n = super::super::sites::MAX_PIECES + 1;
        let ring: Vec<DVec2> = (0..n)
            .map(|i| DVec2::from_angle(i as f64 * TAU / n as f64) * 10.0)
            .collect();
        let f = Figure::Op(
            Op::Union,
            vec![
                Figure::Polygon(Outlines::polygons(vec![ring])),
                Figure::disc(DVec2::new(10.0, 0.0), 1.0),
            ],
        );
        let e = offset(f, Join::Round, -0.5).unwrap_err();
        assert!(e.contains(&format!("more than {} edges", n - 1)), "{e}");
    }
}
