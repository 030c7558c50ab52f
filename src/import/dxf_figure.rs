//! A DXF drawing ([`Drawing`]) as a 2-D tree ([`Figure`]).

use super::dxf::{Arc, Drawing};
use crate::math::boolean::Op;
use crate::plane::figure::Figure;
use crate::plane::Outlines;
use glam::DVec2;

/// A drawing as a 2-D tree (see [`crate::import::dxf`]). Each closed path is
/// the polygon of its chords, minus the circular segments (disc ∩ the
/// chord's half-plane on the arc's side) of arcs bulging inward, plus
/// those bulging outward; a whole circle is a disc. Paths that do not
/// cross nest: one is inside another when a point of its boundary is, its
/// depth how many hold it; the even-odd region is each path of even depth
/// minus the paths directly inside it.
pub fn from_drawing(d: &Drawing) -> Option<Figure> {
    let disc = Figure::disc;
    // Each region: its tree, an inside test, and a point of its boundary.
    struct Piece {
        flat: Figure,
        probe: DVec2,
        chord: Option<Outlines>,
        segs: Vec<(DVec2, DVec2, Arc, bool)>,
        circle: Option<(DVec2, f64)>,
    }
    fn in_segment(x: DVec2, a: DVec2, b: DVec2, arc: &Arc) -> bool {
        let n = (b - a).perp();
        (x - arc.center).length() <= arc.radius
            && ((x - a).dot(n) > 0.0) == ((arc.mid - a).dot(n) > 0.0)
    }
    impl Piece {
        fn contains(&self, x: DVec2) -> bool {
            if let Some((c, r)) = self.circle {
                return (x - c).length() <= r;
            }
            let mut inside = self.chord.as_ref().is_some_and(|o| o.contains(x));
            for (a, b, arc, outward) in &self.segs {
                if in_segment(x, *a, *b, arc) {
                    inside = *outward;
                }
            }
            inside
        }
    }
    let mut pieces: Vec<Piece> = d
        .circles
        .iter()
        .map(|&(c, r)| Piece {
            flat: disc(c, r),
            probe: c + DVec2::new(r, 0.0),
            chord: None,
            segs: Vec::new(),
            circle: Some((c, r)),
        })
        .collect();
    for p in &d.paths {
        let n = p.pts.len();
        let chord = (n >= 3).then(|| Outlines::polygons(vec![p.pts.clone()]));
        let mut segs = Vec::new();
        let (mut inward, mut outward) = (Vec::new(), Vec::new());
        for (i, arc) in p.arcs.iter().enumerate() {
            let Some(arc) = arc else { continue };
            let (a, b) = (p.pts[i], p.pts[(i + 1) % n]);
            let (t, r) = ((b - a).normalize_or_zero(), arc.radius);
            let mut nn = t.perp();
            if (arc.mid - a).dot(nn) < 0.0 {
                nn = -nn;
            }
            let rect = vec![
                a - t * 2.0 * r,
                b + t * 2.0 * r,
                b + t * 2.0 * r + nn * 2.0 * r,
                a - t * 2.0 * r + nn * 2.0 * r,
            ];
            let seg = Figure::Op(
                Op::Intersection,
                vec![
                    disc(arc.center, r),
                    Figure::Polygon(Outlines::polygons(vec![rect])),
                ],
            );
            let out = !chord.as_ref().is_some_and(|o| o.contains(arc.mid));
            if out {
                outward.push(seg);
            } else {
                inward.push(seg);
            }
            segs.push((a, b, *arc, out));
        }
        let body = match chord.clone() {
            Some(o) if inward.is_empty() => Some(Figure::Polygon(o)),
            Some(o) => {
                let mut v = vec![Figure::Polygon(o)];
                v.extend(inward);
                Some(Figure::Op(Op::Difference, v))
            }
            None => None,
        };
        let mut parts: Vec<Figure> = body.into_iter().collect();
        parts.extend(outward);
        let flat = match parts.len() {
            0 => continue,
            1 => parts.pop().unwrap(),
            _ => Figure::Op(Op::Union, parts),
        };
        // A point of the boundary: the middle of the first edge (on its arc
        // when it has one).
        let probe = p.arcs[0].map_or(0.5 * (p.pts[0] + p.pts[1 % n]), |a| a.mid);
        pieces.push(Piece {
            flat,
            probe,
            chord,
            segs,
            circle: None,
        });
    }
    let m = pieces.len();
    let holders: Vec<Vec<usize>> = (0..m)
        .map(|q| {
            (0..m)
                .filter(|&p| p != q && pieces[p].contains(pieces[q].probe))
                .collect()
        })
        .collect();
    let depth: Vec<usize> = if crate::mutant::active("drawing_unnested") {
        vec![0; m]
    } else {
        holders.iter().map(|h| h.len()).collect()
    };
    let mut parts = Vec::new();
    for p in 0..m {
        if depth[p] % 2 == 1 {
            continue;
        }
        let inner: Vec<Figure> = (0..m)
            .filter(|&q| depth[q] == depth[p] + 1 && holders[q].contains(&p))
            .map(|q| pieces[q].flat.clone())
            .collect();
        if inner.is_empty() {
            parts.push(pieces[p].flat.clone());
        } else {
            let mut v = vec![pieces[p].flat.clone()];
            v.extend(inner);
            parts.push(Figure::Op(Op::Difference, v));
        }
    }
    match parts.len() {
        0 => None,
        1 => parts.pop(),
        _ => Some(Figure::Op(Op::Union, parts)),
    }
}
