//! An SVG drawing ([`crate::import::svg`]) as a 2-D tree, exactly.
//!
//! One element's outlines are filled even-odd. Its closed loops of lines
//! and Bézier curves are one [`Outlines`] (even-odd already); an elliptical
//! arc stands in it as its chord, and the region between the chord and the
//! arc — the ellipse cut by the chord's half-plane on the arc's side — is
//! added by parity: even-odd filling is additive mod 2 over closed loops,
//! and arc + chord backwards is the loop around that region. Circles,
//! ellipses and strokes join by the same parity ([`Op::Xor`]), so an
//! element is inside a point exactly where OpenSCAD's even-odd
//! sanitizing of its outlines puts it. Elements are united.
//!
//! A stroke is Clipper's open offset (`ClipperOffset` with its default
//! miter limit 2, as libsvg calls it) made exact: the band of each segment,
//! the ends (square: the band carried on by half the width; round: a disc;
//! butt: nothing) and at each corner, on its outer side, the join — a
//! disc (round), the miter kite where the turn is at most 120° (Clipper's
//! limit: 1 + cos θ ≥ 2/2²), else the kite cut square across the corner's
//! bisector at half the width (Clipper's `DoSquare`, and the `bevel` join
//! libsvg maps to it). A reversal is squared like an end. Clipper rounds
//! the result to libsvg's 10⁻⁴ grid and cuts round parts into pieces;
//! csgrt does neither.

use super::svg::{Seg, Svg, SvgPart, SvgPiece, SvgShape, SvgStroke};
use crate::math::boolean::Op;
use crate::plane::figure::Figure;
use crate::plane::{Ctrl, Outlines};

/// The drawing's tree in OpenSCAD's plane (before the import's own
/// transform).
pub fn from_svg(d: &Svg) -> Option<Figure> {
    let shapes: Vec<Figure> = d
        .shapes
        .iter()
        .filter_map(shape_flat)
        .map(|f| f.moved(d.place))
        .collect();
    match shapes.len() {
        0 => None,
        1 => shapes.into_iter().next(),
        _ => Some(Figure::Op(Op::Union, shapes)),
    }
}

/// One element's region in the page's user space.
fn shape_flat(s: &SvgShape) -> Option<Figure> {
    let (mut loops, mut ctrl, mut odd) = (Vec::new(), Vec::new(), Vec::new());
    for part in &s.parts {
        match part {
            crate::import::svg::SvgPart::Loop(l) => {
                let n = l.pts.len();
                let mut cs = Vec::with_capacity(n);
                for (i, seg) in l.segs.iter().enumerate() {
                    cs.push(match *seg {
                        Seg::Line => Ctrl::Line,
                        Seg::Quad(c) => Ctrl::Quad(c),
                        Seg::Cubic(c1, c2) => Ctrl::Cubic(c1, c2),
                        Seg::Arc { ellipse, mid } => {
                            if !crate::mutant::active("svg_arcs_as_chords") {
                                odd.push(Figure::arc_segment(
                                    l.pts[i],
                                    l.pts[(i + 1) % n],
                                    ellipse,
                                    mid,
                                ));
                            }
                            Ctrl::Line
                        }
                    });
                }
                // Straight loops of fewer than 3 points hold nothing.
                if n >= 3 || cs.iter().any(|c| *c != Ctrl::Line) {
                    loops.push(l.pts.clone());
                    ctrl.push(cs);
                }
            }
            SvgPart::Ellipse(e) => odd.push(Figure::Ellipse(*e)),
            SvgPart::Stroke(st) => odd.extend(stroke_figure(st)),
        }
    }
    let mut parts: Vec<Figure> = Vec::new();
    if !loops.is_empty() {
        parts.push(Figure::Polygon(Outlines { loops, ctrl }));
    }
    parts.extend(odd);
    let f = match parts.len() {
        0 => return None,
        1 => parts.pop().unwrap(),
        _ => Figure::Op(Op::Xor, parts),
    };
    Some(f.moved(s.transform))
}

/// A stroke's exact region: the union of its pieces.
pub fn stroke_figure(st: &SvgStroke) -> Option<Figure> {
    let mut out: Vec<Figure> = st
        .pieces()
        .into_iter()
        .map(|p| match p {
            SvgPiece::Polygon(v) => Figure::Polygon(Outlines::polygons(vec![v])),
            SvgPiece::Disc(c, r) => Figure::disc(c, r),
        })
        .collect();
    match out.len() {
        0 => None,
        1 => out.pop(),
        _ => Some(Figure::Op(Op::Union, out)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::svg::{Cap, SvgJoin};
    use glam::{DAffine2, DVec2};

    /// Whether `p` is in the tree (the ops' meanings, point by point).
    fn inside(f: &Figure, p: DVec2) -> bool {
        match f {
            Figure::Polygon(o) => o.contains(p),
            Figure::Ellipse(e) => e.inverse().transform_point2(p).length() <= 1.0,
            Figure::Op(op, kids) => {
                let mut it = kids.iter().map(|k| inside(k, p));
                match op {
                    Op::Union => it.any(|x| x),
                    Op::Intersection => it.all(|x| x),
                    Op::Difference => it.next().unwrap() && !it.any(|x| x),
                    Op::Xor => it.filter(|&x| x).count() % 2 == 1,
                }
            }
            Figure::Section(..) | Figure::Hull(_) | Figure::Offset(..) => unreachable!(),
        }
    }

    fn stroke(pts: &[(f64, f64)], cap: Cap, join: SvgJoin) -> Figure {
        stroke_figure(&SvgStroke {
            pts: pts.iter().map(|&(x, y)| DVec2::new(x, y)).collect(),
            width: 2.0,
            cap,
            join,
        })
        .unwrap()
    }

    #[test]
    fn a_right_angle_stroke_has_its_square_ends_and_miter() {
        // (0,0) → (10,0) → (10,10), width 2: the miter corner (11, −1),
        // square ends reaching x = −1 and y = 11.
        let f = stroke(
            &[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)],
            Cap::Square,
            SvgJoin::Miter,
        );
        for (p, want) in [
            ((10.9, -0.9), true),
            ((-0.9, 0.9), true),
            ((-1.1, 0.0), false),
            ((10.0, 10.9), true),
            ((10.0, 11.1), false),
            ((5.0, 1.1), false),
            ((8.9, 1.1), false),
        ] {
            assert_eq!(inside(&f, DVec2::new(p.0, p.1)), want, "{p:?}");
        }
        // Butt ends stop at the points; round joins stay within 1.
        let f = stroke(
            &[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)],
            Cap::Butt,
            SvgJoin::Round,
        );
        assert!(!inside(&f, DVec2::new(-0.1, 0.0)));
        assert!(!inside(&f, DVec2::new(10.8, -0.8)));
        assert!(inside(&f, DVec2::new(10.7, -0.7)));
    }

    #[test]
    fn a_sharp_turn_is_squared_at_half_the_width() {
        // A 150° turn: beyond Clipper's 120°, so cut across the bisector
        // at distance 1 from the corner.
        let a = 150f64.to_radians();
        let f = stroke(
            &[(-10.0, 0.0), (0.0, 0.0), (10.0 * a.cos(), 10.0 * a.sin())],
            Cap::Butt,
            SvgJoin::Miter,
        );
        // The bisector of the outer normals points along −(t1 − t2).
        let t1 = DVec2::X;
        let t2 = DVec2::new(a.cos(), a.sin());
        let b = (t1 - t2).normalize();
        assert!(inside(&f, b * 0.999));
        assert!(!inside(&f, b * 1.001));
    }

    #[test]
    fn an_arc_adds_its_segment_by_parity() {
        // A half disc: the chord from (1, 0) to (−1, 0) and the arc over
        // (0, 1); points below the chord are out, those under the arc in.
        let e = DAffine2::IDENTITY;
        let seg = Figure::arc_segment(DVec2::X, -DVec2::X, e, DVec2::Y);
        assert!(inside(&seg, DVec2::new(0.0, 0.5)));
        assert!(inside(&seg, DVec2::new(0.7, 0.7)));
        assert!(!inside(&seg, DVec2::new(0.0, -0.5)));
        assert!(!inside(&seg, DVec2::new(0.0, 1.01)));
    }
}
