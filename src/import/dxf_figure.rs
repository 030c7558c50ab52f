//! A DXF drawing ([`Drawing`]) as a 2-D tree ([`Figure`]).

use super::dxf::Drawing;
use crate::math::boolean::Op;
use crate::plane::figure::Figure;
use crate::plane::Outlines;

/// A drawing as a 2-D tree (see [`crate::import::dxf`]), filled even-odd
/// as OpenSCAD fills it. Even-odd filling is additive mod 2 over closed
/// loops, so the region is the parity ([`Op::Xor`]) of: every path's
/// polygon of chords (one [`Outlines`], even-odd already), each arc's
/// segment (the region between arc and chord: arc + chord backwards is the
/// loop around it) and each whole circle or ellipse.
pub fn from_drawing(d: &Drawing) -> Option<Figure> {
    let mut loops = Vec::new();
    let mut parts: Vec<Figure> = Vec::new();
    for p in &d.paths {
        let n = p.pts.len();
        for (i, arc) in p.arcs.iter().enumerate() {
            if let Some(arc) = arc {
                parts.push(Figure::arc_segment(
                    p.pts[i],
                    p.pts[(i + 1) % n],
                    arc.ellipse,
                    arc.mid,
                ));
            }
        }
        // Straight loops of fewer than 3 points hold nothing.
        if n >= 3 {
            loops.push(p.pts.clone());
        }
    }
    parts.extend(d.ellipses.iter().map(|&e| Figure::Ellipse(e)));
    if !loops.is_empty() {
        parts.insert(0, Figure::Polygon(Outlines::polygons(loops)));
    }
    let op = if crate::mutant::active("dxf_union_fill") {
        Op::Union
    } else {
        Op::Xor
    };
    match parts.len() {
        0 => None,
        1 => parts.pop(),
        _ => Some(Figure::Op(op, parts)),
    }
}
