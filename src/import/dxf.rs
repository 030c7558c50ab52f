//! `import()` of a DXF drawing as OpenSCAD 2021.01 reads one
//! (`src/dxfdata.cc`), with its arcs kept exact.
//!
//! OpenSCAD takes the LINE, LWPOLYLINE, ARC, CIRCLE and (block) INSERT
//! entities of the asked layer (all layers when none is asked), moves each
//! point by −origin and scales it, joins the pieces into paths where their
//! ends meet on a grid of 2⁻²⁰ units, closes a path that does not close
//! with a straight edge back to its start ("to be compatible with existing
//! behavior", `toPolygon2d`), and fills them by the even-odd rule. It cuts arcs into `$fn`
//! pieces; csgrt keeps each as the circle it is: a closed path of lines and
//! arcs is the polygon of its chords, each arc adding (or, bulging inward,
//! removing) its circular segment — a disc cut by the chord's half-plane —
//! and a whole circle is a disc. The file is parsed by the `dxf` crate.

use glam::DVec2;
use std::collections::HashMap;

/// OpenSCAD's grid for joining path ends (`GRID_FINE`).
pub const GRID: f64 = 1.0 / 1048576.0;

/// The most pieces a drawing may have.
pub const MAX_DXF_PIECES: usize = 1_000_000;

/// The most closed paths and circles a drawing may have (their nesting is
/// found by testing every pair).
pub const MAX_PATHS: usize = 5_000;

/// A circular arc from one path point to the next: its circle, and a point
/// of the arc strictly between its ends (which side of the chord it bulges).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    pub center: DVec2,
    pub radius: f64,
    pub mid: DVec2,
}

/// A closed path: edge i runs from `pts[i]` to `pts[i + 1]` (the last back
/// to the first), straight or along `arcs[i]`.
#[derive(Clone, Debug, PartialEq)]
pub struct DxfPath {
    pub pts: Vec<DVec2>,
    pub arcs: Vec<Option<Arc>>,
}

/// A drawing's closed paths and whole circles, ready to fill.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawing {
    pub paths: Vec<DxfPath>,
    pub circles: Vec<(DVec2, f64)>,
    /// The entities left out (of a kind OpenSCAD does not read), by kind.
    pub skipped: Vec<(String, usize)>,
    /// How many paths did not close (and were closed by a straight edge).
    pub open_paths: usize,
}

#[derive(Clone, Copy)]
struct DxfPiece {
    a: DVec2,
    b: DVec2,
    arc: Option<Arc>,
}

fn deg(a: f64) -> (f64, f64) {
    let (s, c) = a.to_radians().sin_cos();
    (s, c)
}

/// An arc of the circle (c, r) from angle a0 to a1 (degrees, counter-
/// clockwise, a1 ≤ a0 meaning one more turn), as OpenSCAD reads an ARC.
fn arc_piece(c: DVec2, r: f64, a0: f64, a1: f64) -> DxfPiece {
    let a1 = if a1 <= a0 { a1 + 360.0 } else { a1 };
    let at = |a: f64| {
        let (s, co) = deg(a);
        c + DVec2::new(co, s) * r
    };
    DxfPiece {
        a: at(a0),
        b: at(a1),
        arc: Some(Arc {
            center: c,
            radius: r,
            mid: at(0.5 * (a0 + a1)),
        }),
    }
}

/// Reads `bytes` (a DXF file) and keeps `layer` (all when empty).
pub fn read(bytes: &[u8], layer: &str, origin: DVec2, scale: f64) -> Result<Drawing, String> {
    let mut reader = std::io::Cursor::new(bytes);
    let d = dxf::Drawing::load(&mut reader).map_err(|e| e.to_string())?;
    let place = |x: f64, y: f64| (DVec2::new(x, y) - origin) * scale;
    let mut out = Drawing::default();
    let mut pieces: Vec<DxfPiece> = Vec::new();
    let mut skipped: HashMap<String, usize> = HashMap::new();
    // The pieces of one entity, in the drawing's units before `place`,
    // under the map m (a block's insertion).
    fn entity_pieces(
        e: &dxf::entities::EntityType,
        m: &dyn Fn(DVec2) -> DVec2,
        k: f64,
        pieces: &mut Vec<DxfPiece>,
        circles: &mut Vec<(DVec2, f64)>,
    ) -> bool {
        use dxf::entities::EntityType as E;
        let p = |x: f64, y: f64| m(DVec2::new(x, y));
        match e {
            E::Line(l) => pieces.push(DxfPiece {
                a: p(l.p1.x, l.p1.y),
                b: p(l.p2.x, l.p2.y),
                arc: None,
            }),
            E::LwPolyline(l) => {
                let v: Vec<DVec2> = l.vertices.iter().map(|v| p(v.x, v.y)).collect();
                for w in v.windows(2) {
                    pieces.push(DxfPiece {
                        a: w[0],
                        b: w[1],
                        arc: None,
                    });
                }
                if l.is_closed() && v.len() > 1 {
                    pieces.push(DxfPiece {
                        a: v[v.len() - 1],
                        b: v[0],
                        arc: None,
                    });
                }
            }
            E::Circle(c) => circles.push((p(c.center.x, c.center.y), c.radius * k)),
            E::Arc(a) => {
                let mut piece = arc_piece(
                    DVec2::new(a.center.x, a.center.y),
                    a.radius,
                    a.start_angle,
                    a.end_angle,
                );
                piece.a = m(piece.a);
                piece.b = m(piece.b);
                if let Some(arc) = piece.arc.as_mut() {
                    arc.center = m(arc.center);
                    arc.mid = m(arc.mid);
                    arc.radius *= k;
                }
                pieces.push(piece);
            }
            _ => return false,
        }
        true
    }
    let placed = |x: DVec2| place(x.x, x.y);
    for e in d.entities() {
        if !layer.is_empty() && e.common.layer != layer {
            continue;
        }
        if let dxf::entities::EntityType::Insert(ins) = &e.specific {
            // A block's pieces, scaled, turned and moved to the insertion
            // point (as OpenSCAD: the block's own layers do not matter).
            let Some(block) = d.blocks().find(|b| b.name == ins.name) else {
                continue;
            };
            let (s, c) = deg(ins.rotation);
            let (sx, sy) = (ins.x_scale_factor, ins.y_scale_factor);
            let at = DVec2::new(ins.location.x, ins.location.y);
            let m = move |q: DVec2| {
                let l = DVec2::new(q.x * sx, q.y * sy);
                placed(DVec2::new(c * l.x - s * l.y, s * l.x + c * l.y) + at)
            };
            for be in &block.entities {
                if !entity_pieces(
                    &be.specific,
                    &m,
                    scale * sx.abs(),
                    &mut pieces,
                    &mut out.circles,
                ) {
                    *skipped.entry(kind_name(&be.specific)).or_default() += 1;
                }
            }
            continue;
        }
        if !entity_pieces(&e.specific, &placed, scale, &mut pieces, &mut out.circles) {
            *skipped.entry(kind_name(&e.specific)).or_default() += 1;
        }
        if pieces.len() > MAX_DXF_PIECES {
            return Err(format!("more than {MAX_DXF_PIECES} pieces"));
        }
    }
    out.skipped = skipped.into_iter().collect();
    out.skipped.sort();
    join(pieces, &mut out);
    if out.paths.len() + out.circles.len() > MAX_PATHS {
        return Err(format!("more than {MAX_PATHS} closed paths and circles"));
    }
    Ok(out)
}

fn kind_name(e: &dxf::entities::EntityType) -> String {
    let s = format!("{e:?}");
    s.split(['(', ' ', '{'])
        .next()
        .unwrap_or("?")
        .to_uppercase()
}

/// Joins pieces into paths where their ends meet on the grid, as OpenSCAD
/// does: first the chains with a free end (open: closed by a straight
/// edge), then the closed loops.
fn join(pieces: Vec<DxfPiece>, out: &mut Drawing) {
    let cell = |p: DVec2| ((p.x / GRID).round() as i64, (p.y / GRID).round() as i64);
    // Points within a grid step are one point: each end's key is the first
    // point seen within one cell.
    let mut keys: HashMap<(i64, i64), usize> = HashMap::new();
    let mut points: Vec<DVec2> = Vec::new();
    let mut key_of = |p: DVec2| -> usize {
        let (i, j) = cell(p);
        for di in -1..=1 {
            for dj in -1..=1 {
                if let Some(&k) = keys.get(&(i + di, j + dj)) {
                    let q = points[k];
                    if (q.x - p.x).abs() <= GRID && (q.y - p.y).abs() <= GRID {
                        return k;
                    }
                }
            }
        }
        points.push(p);
        keys.insert((i, j), points.len() - 1);
        points.len() - 1
    };
    let ends: Vec<(usize, usize)> = pieces.iter().map(|p| (key_of(p.a), key_of(p.b))).collect();
    let mut at: HashMap<usize, Vec<usize>> = HashMap::new();
    for (i, &(a, b)) in ends.iter().enumerate() {
        at.entry(a).or_default().push(i);
        at.entry(b).or_default().push(i);
    }
    let mut used = vec![false; pieces.len()];
    // Follows a chain from piece `first`, entered at its end `from`.
    let walk =
        |first: usize, from: usize, used: &mut Vec<bool>| -> (Vec<usize>, Vec<bool>, usize) {
            let (mut cur, mut point) = (first, from);
            let mut chain = Vec::new();
            let mut forward = Vec::new();
            loop {
                used[cur] = true;
                let fwd = ends[cur].0 == point;
                chain.push(cur);
                forward.push(fwd);
                point = if fwd { ends[cur].1 } else { ends[cur].0 };
                match at[&point].iter().find(|&&k| !used[k]) {
                    Some(&k) => cur = k,
                    None => break,
                }
            }
            (chain, forward, point)
        };
    // A chain's points (each piece's start, as walked) and its pieces' arcs.
    let path_of = |chain: &[usize], forward: &[bool]| -> (Vec<DVec2>, Vec<Option<Arc>>) {
        chain
            .iter()
            .zip(forward)
            .map(|(&k, &fwd)| {
                (
                    points[if fwd { ends[k].0 } else { ends[k].1 }],
                    pieces[k].arc,
                )
            })
            .unzip()
    };
    // Open chains: start at a point no other piece reaches.
    for i in 0..pieces.len() {
        if used[i] {
            continue;
        }
        for end in [ends[i].0, ends[i].1] {
            if used[i] {
                break;
            }
            if at[&end].iter().filter(|&&k| !used[k]).count() == 1 && ends[i].0 != ends[i].1 {
                // OpenSCAD closes it with a straight edge back to its start.
                let (chain, forward, last) = walk(i, end, &mut used);
                out.open_paths += 1;
                let (mut pts, mut arcs) = path_of(&chain, &forward);
                pts.push(points[last]);
                arcs.push(None);
                if pts.len() >= 3 {
                    out.paths.push(DxfPath { pts, arcs });
                }
            }
        }
    }
    for i in 0..pieces.len() {
        if used[i] {
            continue;
        }
        let start = ends[i].0;
        let (chain, forward, last) = walk(i, start, &mut used);
        if last != start {
            out.open_paths += 1;
            continue;
        }
        let (pts, arcs) = path_of(&chain, &forward);
        if pts.len() >= 3 || pts.len() == 2 && arcs.iter().any(|a| a.is_some()) {
            out.paths.push(DxfPath { pts, arcs });
        } else if pts.len() == 1 {
            // A single closed arc is a whole circle.
            if let Some(a) = arcs[0] {
                out.circles.push((a.center, a.radius));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_arc_wraps_past_zero_degrees() {
        let p = arc_piece(DVec2::ZERO, 2.0, 270.0, 90.0);
        assert!((p.a - DVec2::new(0.0, -2.0)).length() < 1e-12);
        assert!((p.b - DVec2::new(0.0, 2.0)).length() < 1e-12);
        // Counter-clockwise from 270 through 0 to 90: the middle at +x.
        assert!((p.arc.unwrap().mid - DVec2::new(2.0, 0.0)).length() < 1e-12);
    }
}

#[cfg(test)]
mod robustness {
    use super::*;

    /// Every prefix of a real drawing, and single-byte changes of it, read
    /// without a panic: an error or a drawing.
    #[test]
    fn truncated_and_corrupted_drawings_never_panic() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/openscad/example009.dxf");
        let bytes = std::fs::read(path).unwrap();
        for cut in (0..bytes.len()).step_by(997) {
            let _ = read(&bytes[..cut], "", DVec2::ZERO, 1.0);
        }
        let mut seed = 7u64;
        for _ in 0..300 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let mut b = bytes.clone();
            let i = (seed >> 20) as usize % b.len();
            b[i] = (seed >> 8) as u8;
            let _ = read(&b, "body", DVec2::ZERO, 1.0);
        }
    }
}
