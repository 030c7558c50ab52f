//! The even-odd region of loops in the plane cut into trapezoids between
//! levels across one direction — the convex pieces a shadow's prisms take,
//! so that each piece is as low as the outline's own levels make it and
//! meets only the pieces of another solid at its levels (a triangulation's
//! long slivers each meet most of them).

use glam::DVec2;

/// An edge from its low end to its high end (levels `ha` < `hb`).
#[derive(Clone, Copy)]
struct Edge {
    a: DVec2,
    b: DVec2,
    ha: f64,
    hb: f64,
}

impl Edge {
    /// The edge's point at level `h` (its own ends exactly).
    fn at(&self, h: f64) -> DVec2 {
        if h <= self.ha {
            self.a
        } else if h >= self.hb {
            self.b
        } else {
            self.a + (self.b - self.a) * ((h - self.ha) / (self.hb - self.ha))
        }
    }
}

/// The even-odd region of `loops` as convex pieces between lines across
/// `up` (a nonzero direction): through every corner's level, each band's
/// inside spans between consecutive crossing edges, a span continued
/// upward while the same two edges bound it. `None` where two edges cross
/// between levels (an outline that crosses itself): no trapezoid has them
/// as sides.
pub fn trapezoids(loops: &[Vec<DVec2>], up: DVec2) -> Option<Vec<Vec<DVec2>>> {
    let side = DVec2::new(up.y, -up.x);
    let mut edges = Vec::new();
    for l in loops {
        for (i, &p) in l.iter().enumerate() {
            let q = l[(i + 1) % l.len()];
            let (hp, hq) = (p.dot(up), q.dot(up));
            if hp < hq {
                edges.push(Edge {
                    a: p,
                    b: q,
                    ha: hp,
                    hb: hq,
                });
            } else if hq < hp {
                edges.push(Edge {
                    a: q,
                    b: p,
                    ha: hq,
                    hb: hp,
                });
            }
        }
    }
    edges.sort_by(|x, y| x.ha.total_cmp(&y.ha));
    let mut levels: Vec<f64> = edges.iter().flat_map(|e| [e.ha, e.hb]).collect();
    levels.sort_by(f64::total_cmp);
    levels.dedup();
    let mut out = Vec::new();
    // Edges crossing the band, and the spans open below it: (left edge,
    // right edge, the level they start at).
    let mut active: Vec<usize> = Vec::new();
    let mut open: Vec<(usize, usize, f64)> = Vec::new();
    let mut next = 0;
    for w in levels.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        active.retain(|&k| edges[k].hb > lo);
        while next < edges.len() && edges[next].ha <= lo {
            active.push(next);
            next += 1;
        }
        let mid = 0.5 * (lo + hi);
        active.sort_by(|&x, &y| {
            edges[x]
                .at(mid)
                .dot(side)
                .total_cmp(&edges[y].at(mid).dot(side))
        });
        // Crossing between levels: the order at the band's ends differs.
        for k in active.windows(2) {
            let (x, y) = (&edges[k[0]], &edges[k[1]]);
            if x.at(lo).dot(side) > y.at(lo).dot(side) || x.at(hi).dot(side) > y.at(hi).dot(side) {
                return None;
            }
        }
        let spans: Vec<(usize, usize)> = active.chunks_exact(2).map(|k| (k[0], k[1])).collect();
        let mut still = Vec::with_capacity(spans.len());
        for &(l, r, from) in &open {
            if spans.contains(&(l, r)) {
                still.push((l, r, from));
            } else {
                out.extend(piece(&edges[l], &edges[r], from, lo));
            }
        }
        for &(l, r) in &spans {
            if !still.iter().any(|&(a, b, _)| (a, b) == (l, r)) {
                still.push((l, r, lo));
            }
        }
        open = still;
    }
    // The fault: the pieces still open at the top level left out.
    if crate::mutant::active("trapezoids_top_dropped") {
        return Some(out);
    }
    if let Some(&top) = levels.last() {
        for &(l, r, from) in &open {
            out.extend(piece(&edges[l], &edges[r], from, top));
        }
    }
    Some(out)
}

/// The part between edges `l` and `r` from level `lo` to `hi`, counter-
/// clockwise, its repeated corners (where the edges meet) once.
fn piece(l: &Edge, r: &Edge, lo: f64, hi: f64) -> Option<Vec<DVec2>> {
    let mut pts = vec![l.at(lo), r.at(lo), r.at(hi), l.at(hi)];
    pts.dedup();
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    (pts.len() >= 3).then_some(pts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::triangulate::signed_area;

    /// The pieces' areas summed (`signed_area` is twice a loop's).
    fn area(pieces: &[Vec<DVec2>]) -> f64 {
        pieces.iter().map(|p| 0.5 * signed_area(p)).sum()
    }

    /// A square with a square hole, at an angle: the pieces' areas add up
    /// to the region's (16 − 4), each turned counterclockwise, and every
    /// piece lies between two of the seven corners' levels.
    #[test]
    fn holed_square_areas() {
        let outer = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 4.0),
            DVec2::new(0.0, 4.0),
        ];
        let hole = vec![
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 3.0),
            DVec2::new(3.0, 3.0),
            DVec2::new(3.0, 1.0),
        ];
        let up = DVec2::new(1.0, 2.0).normalize();
        let pieces = trapezoids(&[outer, hole], up).unwrap();
        assert!((area(&pieces) - 12.0).abs() < 1e-12, "{}", area(&pieces));
        assert!(pieces.iter().all(|p| signed_area(p) > 0.0));
        assert!(pieces.iter().all(|p| crate::plane::hull::convex_polygon(p)));
    }

    /// A bow tie (a loop crossing itself between levels) is refused.
    #[test]
    fn crossing_refused() {
        let bow = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(0.0, 2.0),
        ];
        assert!(trapezoids(&[bow], DVec2::Y).is_none());
    }

    /// Along y the pieces of a comb (an E on its back) are its bands: the
    /// spine below, each tooth one piece above it.
    #[test]
    fn comb_bands() {
        let comb = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(5.0, 0.0),
            DVec2::new(5.0, 3.0),
            DVec2::new(4.0, 3.0),
            DVec2::new(4.0, 1.0),
            DVec2::new(3.0, 1.0),
            DVec2::new(3.0, 3.0),
            DVec2::new(2.0, 3.0),
            DVec2::new(2.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 3.0),
            DVec2::new(0.0, 3.0),
        ];
        let pieces = trapezoids(&[comb], DVec2::Y).unwrap();
        assert_eq!(pieces.len(), 4);
        assert!((area(&pieces) - 11.0).abs() < 1e-12);
    }
}
