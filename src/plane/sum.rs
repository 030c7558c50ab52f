//! OpenSCAD's 2-D `minkowski()` of figures, exactly: circles sum to one
//! circle that grows the rest, convex pieces sum by the hull of their
//! corners' sums, and a union distributes over its pieces.

use super::figure::{is_circle, Figure};
use super::hull::{convex_polygon, hull_indices_2d};
use super::offset::Join;
use super::Outlines;
use crate::math::boolean::{combine_parts, Op};
use glam::{DAffine2, DVec2};

/// The most convex pieces a 2-D Minkowski sum is the union of, and the
/// most corners of one.
const MAX_SUM_PIECES: usize = 10_000;

/// A convex piece of an operand: the hull of its points, grown by a disc
/// of its radius (a polygon's corners with radius zero, a circle's centre
/// with its own).
type Piece2 = (Vec<DVec2>, f64);

/// OpenSCAD's 2-D `minkowski()` of `ops` (in their own frame), exactly.
/// Circles sum to one circle, which grows the rest by its radius: the
/// offset of any one other shape (a rounded outline), or, for convex
/// pieces, the disc about their sum. Convex operands sum by the hull of
/// their corners' sums, and a union distributes over its pieces,
/// A ⊕ (B ∪ C) = (A ⊕ B) ∪ (A ⊕ C).
pub fn minkowski(ops: Vec<Figure>) -> Result<Option<Figure>, String> {
    let (mut c, mut r) = (DVec2::ZERO, 0.0);
    let mut rest = Vec::new();
    for f in ops {
        match &f {
            Figure::Ellipse(e) if is_circle(e.matrix2) => {
                c += e.translation;
                r += e.matrix2.x_axis.length();
            }
            _ => rest.push(f),
        }
    }
    let mut pieces: Vec<Vec<Piece2>> = Vec::new();
    let mut whole = Vec::new();
    for f in rest {
        let mut p = Vec::new();
        if convex_pieces(&f, &mut p) {
            pieces.push(p);
        } else {
            whole.push(f);
        }
    }
    let to_centre = DAffine2::from_translation(c);
    match (whole.len(), pieces.is_empty()) {
        (0, _) => {}
        (1, false) if r == 0.0 => return polygon_plus(&whole[0], &pieces),
        (1, true) => {
            let f = whole.pop().expect("one");
            let grown = if r > 0.0 {
                super::offset::offset(f, Join::Round, r)?
            } else {
                Some(f)
            };
            return Ok(grown.map(|g| g.moved(to_centre)));
        }
        _ => return Err(not_summed()),
    }
    if pieces.is_empty() {
        return Ok((r > 0.0).then(|| Figure::disc(c, r)));
    }
    let parts: Vec<Option<Figure>> = choices((vec![c], r), &pieces)?
        .into_iter()
        .map(|(pts, r)| grown_polygon(&pts, r))
        .collect();
    Ok(combine_parts(Op::Union, parts, Figure::Op))
}

/// A polygon A that is not convex plus a union of convex polygons: for
/// each choice B of one piece from each operand (B the hull of their
/// corners' sums), A moved by B's first corner b, and each edge of A plus
/// B (the hull of its ends' sums with B's corners) — A ⊕ B = (A + b) ∪
/// (∂A ⊕ B) for a convex B: on the segment from b to any other point of B,
/// a point of the sum leaves A + b only across A's boundary.
fn polygon_plus(a: &Figure, pieces: &[Vec<Piece2>]) -> Result<Option<Figure>, String> {
    let loops = match a {
        Figure::Polygon(o) if !o.curved() => &o.loops,
        _ => return Err(not_summed()),
    };
    let combos = choices((vec![DVec2::ZERO], 0.0), pieces)?;
    if combos.iter().any(|(_, r)| *r != 0.0) {
        return Err(not_summed());
    }
    let edges: usize = loops.iter().map(|l| l.len()).sum();
    if combos.len() * (edges + 1) > MAX_SUM_PIECES {
        return Err(format!(
            "a 2-D `minkowski` of more than {MAX_SUM_PIECES} convex pieces"
        ));
    }
    let mut parts = Vec::new();
    for (b, _) in &combos {
        parts.push(Some(a.clone().moved(DAffine2::from_translation(b[0]))));
        for l in loops {
            for i in 0..l.len() {
                let (p, q) = (l[i], l[(i + 1) % l.len()]);
                let hull = hull2(b.iter().flat_map(|&x| [p + x, q + x]).collect());
                if hull.len() >= 3 {
                    parts.push(Some(Figure::Polygon(Outlines::polygons(vec![hull]))));
                }
            }
        }
    }
    Ok(combine_parts(Op::Union, parts, Figure::Op))
}

/// Every choice of one convex piece from each of `pieces`, summed onto
/// `start`: the hull of the corners' sums, with the radii's sum.
fn choices(start: Piece2, pieces: &[Vec<Piece2>]) -> Result<Vec<Piece2>, String> {
    let mut combos = vec![start];
    for op in pieces {
        let mut next = Vec::with_capacity(combos.len() * op.len());
        for (acc, ra) in &combos {
            for (pts, rb) in op {
                let sum: Vec<DVec2> = acc
                    .iter()
                    .flat_map(|&a| pts.iter().map(move |&b| a + b))
                    .collect();
                next.push((hull2(sum), ra + rb));
            }
        }
        if next.len() > MAX_SUM_PIECES {
            return Err(format!(
                "a 2-D `minkowski` of more than {MAX_SUM_PIECES} convex pieces"
            ));
        }
        combos = next;
    }
    Ok(combos)
}

/// The most pieces a 2-D Minkowski sum of shapes that are not convex is
/// the union of ([`convolved`]: a parallelogram for each pair of edges).
pub const MAX_CONVOLVED: usize = 250_000;

/// The 2-D `minkowski()` of straight polygons and their combinations,
/// and of circles (each operand flattened first, but for a circle on its
/// own), exactly: the circles sum to one, which grows the sum of the rest
/// by its radius ([`super::offset::offset`]), and two shapes A and B sum
/// to
///
///   A ⊕ B = ⋃ (k₀ + B) ∪ ⋃ (A + l₀) ∪ ⋃ (e ⊕ f),
///
/// k₀ a corner of each loop K of A's boundary, l₀ of each loop L of B's,
/// e and f any edges of the two boundaries (e ⊕ f a parallelogram). For x
/// = a + b: a path in A from a to the k₀ of its part (every part of A has
/// a loop of its boundary) moves x − a′ out of B across ∂B, or leaves it
/// in B, so x ∈ k₀ + B or x ∈ A ⊕ ∂B; and along the loop L through that
/// point of ∂B, to l₀, x − l′ leaves A across ∂A or stays in it, so x ∈
/// ∂A ⊕ ∂B or x ∈ A + l₀. Each piece lies in the sum, as the edges lie in
/// their shapes.
pub fn convolved(ops: Vec<Figure>) -> Result<Option<Figure>, String> {
    let (mut c, mut r) = (DVec2::ZERO, 0.0);
    let mut sum: Option<Figure> = None;
    for f in ops {
        match &f {
            Figure::Ellipse(e) if is_circle(e.matrix2) => {
                c += e.translation;
                r += e.matrix2.x_axis.length();
            }
            _ => {
                sum = Some(match sum {
                    None => f,
                    Some(a) => match pair(&a, &f)? {
                        Some(s) => s,
                        None => return Ok(None),
                    },
                })
            }
        }
    }
    let Some(sum) = sum else {
        return Ok((r > 0.0).then(|| Figure::disc(c, r)));
    };
    let grown = if r > 0.0 {
        super::offset::offset(sum, Join::Round, r)?
    } else {
        Some(sum)
    };
    Ok(grown.map(|g| g.moved(DAffine2::from_translation(c))))
}

/// A ⊕ B for two straight figures (above).
fn pair(a: &Figure, b: &Figure) -> Result<Option<Figure>, String> {
    let (Some(ka), Some(kb)) = (boundary(a), boundary(b)) else {
        return Err(not_summed());
    };
    if ka.is_empty() || kb.is_empty() {
        // An empty operand: an empty sum.
        return Ok(None);
    }
    let edges = |k: &[Vec<DVec2>]| k.iter().map(|l| l.len()).sum::<usize>();
    if edges(&ka) * edges(&kb) + ka.len() + kb.len() > MAX_CONVOLVED {
        return Err(format!(
            "a 2-D `minkowski` of more than {MAX_CONVOLVED} pieces (a parallelogram for each pair of edges)"
        ));
    }
    let mut parts = Vec::new();
    for k in &ka {
        parts.push(Some(b.moved(DAffine2::from_translation(k[0]))));
    }
    for l in &kb {
        parts.push(Some(a.moved(DAffine2::from_translation(l[0]))));
    }
    let sides = |k: &[Vec<DVec2>]| -> Vec<(DVec2, DVec2)> {
        k.iter()
            .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
            .collect()
    };
    let (ea, eb) = (sides(&ka), sides(&kb));
    for &(p, q) in &ea {
        for &(u, v) in &eb {
            let (e, f) = (q - p, v - u);
            if e.perp_dot(f) == 0.0 || crate::mutant::active("sum_edges_skipped") {
                // Parallel (or empty): a segment, which adds no area.
                continue;
            }
            // p + u, then along e, then along f, back: counter-clockwise
            // when e turns left into f.
            let mut quad = vec![p + u, q + u, q + v, p + v];
            if e.perp_dot(f) < 0.0 {
                quad.reverse();
            }
            parts.push(Some(Figure::Polygon(Outlines::polygons(vec![quad]))));
        }
    }
    Ok(combine_parts(Op::Union, parts, Figure::Op))
}

/// Loops whose edges hold the boundary of a straight figure and lie in it,
/// with a loop in each part of it: a polygon's own loops, a union's
/// parts' loops, another combination's outline (none when it is empty);
/// `None` for anything else.
fn boundary(f: &Figure) -> Option<Vec<Vec<DVec2>>> {
    match f {
        Figure::Polygon(o) if !o.curved() => Some(o.loops.clone()),
        Figure::Op(Op::Union, kids) => {
            let mut out = Vec::new();
            for k in kids {
                out.extend(boundary(k)?);
            }
            Some(out)
        }
        // A combination with no outline is empty when it has no boundary.
        Figure::Op(..) => match super::sites::touching_outline(f) {
            Some(o) => Some(o.loops),
            None => match super::sites::strokes(f) {
                Some((s, _)) if s.is_empty() => Some(Vec::new()),
                _ => None,
            },
        },
        _ => None,
    }
}

fn not_summed() -> String {
    format!(
        "a 2-D `minkowski` of shapes that are not convex, whose outline csgrt cannot read (curves, ellipses, or more than {} edges)",
        super::sites::MAX_PIECES
    )
}

/// The convex pieces of a union of convex polygons and circles; false for
/// anything else.
fn convex_pieces(f: &Figure, out: &mut Vec<Piece2>) -> bool {
    match f {
        Figure::Ellipse(e) if is_circle(e.matrix2) => {
            out.push((vec![e.translation], e.matrix2.x_axis.length()));
            true
        }
        Figure::Polygon(o) if !o.curved() && o.loops.len() == 1 && convex_polygon(&o.loops[0]) => {
            out.push((hull2(o.loops[0].clone()), 0.0));
            true
        }
        Figure::Op(Op::Union, kids) => kids.iter().all(|k| convex_pieces(k, out)),
        _ => false,
    }
}

/// The corners of the convex hull of points, counter-clockwise (points on
/// an edge left out); the one point, when they are all one (a circle's
/// centre summed with a point: the piece is that circle).
fn hull2(pts: Vec<DVec2>) -> Vec<DVec2> {
    let corners: Vec<DVec2> = hull_indices_2d(&pts, 0.0)
        .into_iter()
        .map(|i| pts[i])
        .collect();
    if corners.is_empty() && !crate::mutant::active("sum_circle_dropped") {
        return pts.into_iter().take(1).collect();
    }
    corners
}

/// The convex polygon of `corners` (counter-clockwise) grown by a disc of
/// radius r: each edge moved out by r, with a disc on each corner.
fn grown_polygon(corners: &[DVec2], r: f64) -> Option<Figure> {
    let mut parts: Vec<Option<Figure>> = Vec::new();
    if r > 0.0 {
        parts.extend(corners.iter().map(|&p| Some(Figure::disc(p, r))));
    }
    let n = corners.len();
    let poly = if n >= 3 && r > 0.0 {
        let mut out = Vec::with_capacity(2 * n);
        for i in 0..n {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            let e = (b - a).normalize();
            let out_n = DVec2::new(e.y, -e.x) * r;
            out.push(a + out_n);
            out.push(b + out_n);
        }
        Some(out)
    } else if n == 2 && r > 0.0 {
        let e = (corners[1] - corners[0]).normalize();
        let side = DVec2::new(e.y, -e.x) * r;
        Some(vec![
            corners[0] + side,
            corners[1] + side,
            corners[1] - side,
            corners[0] - side,
        ])
    } else if n >= 3 {
        Some(corners.to_vec())
    } else {
        None
    };
    parts.extend(poly.map(|p| Some(Figure::Polygon(Outlines::polygons(vec![p])))));
    combine_parts(Op::Union, parts, Figure::Op)
}
