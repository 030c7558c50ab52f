//! The plane's certified approximation: a figure flattened to straight
//! polygons within a stated distance, for the operations csgrt has no
//! exact form of (an offset of an ellipse or of a combination with curves
//! in it, a turn of an ellipse across the axis, a twist of text, a sum of
//! two shapes that are not convex).
//!
//! Each leaf moves by at most ε: a curved edge becomes chords within ε of
//! it (a Bézier curve lies in the hull of its control points, so one whose
//! inner control points are within ε of its chord is within ε of that
//! chord; others are halved, de Casteljau, until they are); an ellipse the
//! polygon of n points with σ(1 − cos(π/n)) ≤ ε, σ its largest stretch; a
//! hull the hull of its flattened parts (the hull moves no farther than
//! its parts); an offset of curved outlines the exact offset of its
//! flattened outlines (an offset moves no farther than what it offsets:
//! the distance to a set changes by at most the sets' distance). The
//! unions, intersections and differences of leaves each within ε of their
//! own are within ε of the exact combination.

use super::figure::{is_circle, Figure};
use super::hull::hull_indices_2d;
use super::offset::{grown_flat, offset, Join};
use super::Outlines;
use glam::{DAffine2, DMat2, DVec2};

/// The most chords one ellipse is cut into.
pub const MAX_CHORDS: usize = 1 << 16;

/// `f` with its curved leaves flattened within `eps` (circles kept exact
/// when `circles`: the offsets and sums that take them); `Ok(None)` when
/// nothing with area is left; `Err` names a leaf this cannot flatten (a
/// projection, whose solid is read only when it is extruded).
pub fn flattened(f: &Figure, eps: f64, circles: bool) -> Result<Option<Figure>, String> {
    Ok(match f {
        Figure::Polygon(o) if o.curved() => {
            Some(Figure::Polygon(Outlines::polygons(chords(o, eps))))
        }
        Figure::Polygon(_) => Some(f.clone()),
        Figure::Ellipse(e) if circles && is_circle(e.matrix2) => Some(f.clone()),
        Figure::Ellipse(e) => {
            ellipse(*e, eps).map(|l| Figure::Polygon(Outlines::polygons(vec![l])))
        }
        Figure::Section(..) => return Err("a projection".into()),
        Figure::Op(op, kids) => {
            let mut parts = Vec::new();
            for k in kids {
                parts.push(flattened(k, eps, circles)?);
            }
            crate::math::boolean::combine_parts(*op, parts, Figure::Op)
        }
        Figure::Hull(kids) => {
            let mut pts = Vec::new();
            for k in kids {
                if let Some(k) = flattened(k, eps, false)? {
                    corners(&k, &mut pts);
                }
            }
            let size = spread(&pts);
            let hull: Vec<DVec2> = hull_indices_2d(&pts, 1e-12 * size)
                .into_iter()
                .map(|i| pts[i])
                .collect();
            (hull.len() >= 3).then(|| Figure::Polygon(Outlines::polygons(vec![hull])))
        }
        Figure::Offset(o, at) => {
            // Half the error before the map, half after it.
            let sigma = largest_stretch(at.matrix2);
            if !(sigma > 0.0 && sigma.is_finite()) {
                return Ok(None);
            }
            let inner = Outlines::polygons(chords(&o.region.outlines, 0.5 * eps / sigma));
            // Kept circles stay the corners' discs; else each corner's
            // sector, flattened before the map as the chords are.
            let grown = if circles {
                offset(Figure::Polygon(inner), Join::Round, o.r)?
            } else {
                grown_flat(inner, o.r, 0.5 * eps / sigma)?
            };
            match grown {
                Some(g) => flattened(&g.moved(*at), 0.5 * eps, circles)?,
                None => None,
            }
        }
    })
}

/// Whether [`flattened`] would leave `f` as it is (straight polygons, and
/// circles when they are kept).
pub fn straight(f: &Figure, circles: bool) -> bool {
    match f {
        Figure::Polygon(o) => !o.curved(),
        Figure::Ellipse(e) => circles && is_circle(e.matrix2),
        Figure::Op(_, kids) => kids.iter().all(|k| straight(k, circles)),
        _ => false,
    }
}

/// Every corner of a flattened figure's polygons.
fn corners(f: &Figure, out: &mut Vec<DVec2>) {
    match f {
        Figure::Polygon(o) => out.extend(o.loops.iter().flatten()),
        Figure::Op(_, kids) | Figure::Hull(kids) => kids.iter().for_each(|k| corners(k, out)),
        _ => {}
    }
}

/// The largest coordinate's size among `pts` (1 when there are none).
fn spread(pts: &[DVec2]) -> f64 {
    pts.iter().fold(1.0f64, |m, p| m.max(p.abs().max_element()))
}

/// The largest singular value of a 2×2 matrix M (the farthest point of
/// the ellipse M·(unit disc) from its centre): [`gram_stretch`] of MᵀM.
pub fn largest_stretch(m: DMat2) -> f64 {
    gram_stretch(m.transpose() * m)
}

/// The square root of the larger eigenvalue of a symmetric 2×2 matrix G
/// [[a, b], [b, d]], ½(a + d + √((a − d)² + 4b²)): the largest stretch of
/// any map whose columns' dot products G holds (MᵀM for a 2×2 M; the
/// Gram matrix of two vectors in space).
pub fn gram_stretch(g: DMat2) -> f64 {
    let (a, b, d) = (g.x_axis.x, g.x_axis.y, g.y_axis.y);
    (0.5 * (a + d + ((a - d).powi(2) + 4.0 * b * b).sqrt()))
        .max(0.0)
        .sqrt()
}

/// The ellipse `e` (the image of the unit circle) as the polygon of its n
/// points at equal angles of the circle, n the least with σ(1 − cos(π/n))
/// ≤ eps (a chord of the circle strays 1 − cos(π/n) from it, and the map
/// stretches that by at most σ), counter-clockwise; `None` when it is
/// flat.
pub fn ellipse(e: DAffine2, eps: f64) -> Option<Vec<DVec2>> {
    let det = e.matrix2.determinant();
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let sigma = largest_stretch(e.matrix2);
    let gap = (eps / sigma).min(1.0);
    let n = ((std::f64::consts::PI / (1.0 - gap).acos()).ceil() as usize).clamp(8, MAX_CHORDS);
    let n = if crate::mutant::active("flat_coarse") {
        (n / 4).max(3)
    } else {
        n
    };
    let mut l: Vec<DVec2> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            e.transform_point2(DVec2::from_angle(a))
        })
        .collect();
    if det < 0.0 {
        l.reverse();
    }
    Some(l)
}

/// The loops of `o` with each curved edge replaced by chords within `tol`
/// of it (above).
pub fn chords(o: &Outlines, tol: f64) -> Vec<Vec<DVec2>> {
    fn chord(p: &[DVec2], tol: f64, depth: usize, out: &mut Vec<DVec2>) {
        let (a, b) = (p[0], p[p.len() - 1]);
        let far = p[1..p.len() - 1]
            .iter()
            .map(|&c| match (b - a).try_normalize() {
                Some(u) => u.perp_dot(c - a).abs(),
                None => (c - a).length(),
            })
            .fold(0.0f64, f64::max);
        if far <= tol || depth >= 24 {
            out.push(b);
            return;
        }
        // de Casteljau at ½: the two halves' control points.
        let mut rows = vec![p.to_vec()];
        while rows.last().map_or(0, Vec::len) > 1 {
            let r = rows.last().expect("a row");
            rows.push(r.windows(2).map(|w| (w[0] + w[1]) * 0.5).collect());
        }
        let left: Vec<DVec2> = rows.iter().map(|r| r[0]).collect();
        let right: Vec<DVec2> = rows.iter().rev().map(|r| r[r.len() - 1]).collect();
        chord(&left, tol, depth + 1, out);
        chord(&right, tol, depth + 1, out);
    }
    o.loops
        .iter()
        .enumerate()
        .map(|(j, l)| {
            let c = o.ctrl.get(j);
            let mut out = Vec::with_capacity(l.len());
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                let mut p = vec![a];
                p.extend(
                    c.and_then(|c| c.get(i))
                        .map_or(Vec::new(), |k| k.points().collect()),
                );
                p.push(b);
                out.push(a);
                if p.len() > 2 {
                    chord(&p, tol, 0, &mut out);
                    // The loop's next point is pushed by the next edge.
                    out.pop();
                }
            }
            out
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slanted_ellipse_stays_within_eps_and_inside() {
        // x²/9 + y²/1 ≤ 1 turned by 30°: every chord's middle within eps
        // of the ellipse, measured by the exact distance along its normal
        // direction's scale (the implicit form, scaled by the gradient).
        let e = DAffine2::from_angle(0.5) * DAffine2::from_scale(DVec2::new(3.0, 1.0));
        for eps in [1e-1, 1e-3, 1e-5] {
            let l = ellipse(e, eps).unwrap();
            let inv = e.inverse();
            for i in 0..l.len() {
                let mid = (l[i] + l[(i + 1) % l.len()]) * 0.5;
                let q = inv.transform_point2(mid);
                // Inside the ellipse.
                assert!(q.length() <= 1.0 + 1e-12);
                // The nearest point of the ellipse is nearer than eps: the
                // point pushed out along the ray from the centre by eps
                // reaches past it (the ray's stretch is at most 3).
                let out = inv.transform_point2(mid + (mid - e.translation).normalize() * eps);
                assert!(out.length() >= 1.0 - 1e-12, "{eps} {}", out.length());
            }
        }
        assert!(largest_stretch(e.matrix2) > 3.0 - 1e-12);
        assert!(largest_stretch(e.matrix2) < 3.0 + 1e-9);
    }

    #[test]
    fn a_quadratic_edge_becomes_chords_within_tol() {
        // The parabola from (0,0) to (2,0) through control (1,2): y = 2x − x².
        let o = Outlines {
            loops: vec![vec![DVec2::ZERO, DVec2::new(2.0, 0.0)]],
            ctrl: vec![vec![
                super::super::Ctrl::Quad(DVec2::new(1.0, 2.0)),
                super::super::Ctrl::Line,
            ]],
        };
        for tol in [1e-2, 1e-4] {
            let l = &chords(&o, tol)[0];
            assert!(l.len() > 4);
            for w in l.windows(2) {
                let mid = (w[0] + w[1]) * 0.5;
                let exact = 2.0 * mid.x - mid.x * mid.x;
                if w[1].y > 0.0 || w[0].y > 0.0 {
                    assert!((exact - mid.y).abs() <= tol + 1e-12, "{tol}");
                }
            }
        }
    }
}
