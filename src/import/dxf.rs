//! `import()` of a DXF drawing as OpenSCAD 2021.01 reads one
//! (`src/dxfdata.cc`), with its arcs kept exact.
//!
//! OpenSCAD takes the LINE, LWPOLYLINE, ARC, CIRCLE, ELLIPSE and (block)
//! INSERT entities of the asked layer (all layers when none is asked), moves
//! each point by −origin and scales it, joins the pieces into paths where
//! their ends meet on its coarse grid of 2⁻¹⁰ units (`GRID_COARSE`): first
//! the chains with a free end, each closed by a straight edge back to its
//! start ("to be compatible with existing behavior", `toPolygon2d`), then
//! the rest, each followed from its first piece until no piece goes on —
//! a chain that stops away from its start is still a path, without one
//! end (`toPolygon2d` leaves a closed path's first index out, after
//! `fixup_path_direction` may have turned it round) — and
//! fills all paths together by the even-odd rule (`ClipperUtils::sanitize`).
//! It cuts arcs and ellipses into `$fn` pieces; csgrt keeps each as the
//! curve it is. The file is parsed by the `dxf` crate.
//!
//! Two slips of OpenSCAD's ELLIPSE reading are not followed: it moves the
//! major axis (a direction) by −origin like a point, and scales the axis
//! ratio by `scale` as if it were a radius; csgrt places the ellipse as
//! the drawing's map places any curve.

use glam::{DAffine2, DMat2, DVec2};
use std::collections::HashMap;

/// OpenSCAD's grid for joining path ends (`GRID_COARSE`).
pub const GRID: f64 = 1.0 / 1024.0;

/// The most pieces a drawing may have.
pub const MAX_DXF_PIECES: usize = 1_000_000;

/// The most closed paths and whole curves a drawing may have.
pub const MAX_PATHS: usize = 5_000;

/// An arc of an ellipse from one path point to the next: the ellipse (the
/// image of the unit circle), and a point of the arc strictly between its
/// ends (which side of the chord it bulges).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DxfArc {
    pub ellipse: DAffine2,
    pub mid: DVec2,
}

/// A closed path: edge i runs from `pts[i]` to `pts[i + 1]` (the last back
/// to the first), straight or along `arcs[i]`.
#[derive(Clone, Debug, PartialEq)]
pub struct DxfPath {
    pub pts: Vec<DVec2>,
    pub arcs: Vec<Option<DxfArc>>,
}

/// A drawing's closed paths and whole circles and ellipses, ready to fill.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawing {
    pub paths: Vec<DxfPath>,
    /// Whole circles and ellipses, each the image of the unit disc.
    pub ellipses: Vec<DAffine2>,
    /// The entities left out (of a kind OpenSCAD does not read), by kind.
    pub skipped: Vec<(String, usize)>,
    /// How many paths did not close (and were closed by a straight edge).
    pub open_paths: usize,
}

#[derive(Clone, Copy)]
struct DxfPiece {
    a: DVec2,
    b: DVec2,
    arc: Option<DxfArc>,
}

/// The piece of `ellipse` from parameter w0 to w1 (radians, w1 > w0), or
/// the whole ellipse when it goes all the way round.
fn ellipse_piece(ellipse: DAffine2, w0: f64, w1: f64) -> Result<DxfPiece, DAffine2> {
    if w1 - w0 >= std::f64::consts::TAU {
        return Err(ellipse);
    }
    let at = |w: f64| ellipse.transform_point2(DVec2::new(w.cos(), w.sin()));
    Ok(DxfPiece {
        a: at(w0),
        b: at(w1),
        arc: Some(DxfArc {
            ellipse,
            mid: at(0.5 * (w0 + w1)),
        }),
    })
}

/// How many straight pieces a full turn of radius r is cut into, if any.
pub type Cut<'a> = &'a dyn Fn(f64) -> Option<usize>;

/// One entity's pieces and whole curves under the map `m` (the drawing's
/// placement, after a block's insertion), its curves cut by `cut` at
/// their radius times k (the drawing's scale; 1 in a block, as OpenSCAD
/// reads them); false for a kind not read.
fn entity_pieces(
    e: &dxf::entities::EntityType,
    m: DAffine2,
    (cut, k): (Cut, f64),
    pieces: &mut Vec<DxfPiece>,
    ellipses: &mut Vec<DAffine2>,
) -> bool {
    use dxf::entities::EntityType as E;
    let p = |x: f64, y: f64| m.transform_point2(DVec2::new(x, y));
    // A curve: its own ellipse placed, and (OpenSCAD's reading) from w0 to
    // w1 counter-clockwise, w1 moved on by turns while below w0; no piece
    // when they are equal. Where `cut` gives the fragments of a full turn
    // at radius r (OpenSCAD's `get_fragments_from_r` at the drawing's
    // size), it is cut into ⌈fragments · sweep / turn⌉ straight pieces, as
    // OpenSCAD cuts every arc; else it stays the curve it is.
    let mut curve = |own: DAffine2, w0: f64, mut w1: f64, r: f64| {
        while w0 > w1 {
            w1 += std::f64::consts::TAU;
        }
        if w1 == w0 {
            return;
        }
        let placed = m * own;
        if let Some(n) = cut(r * k) {
            let count = (n as f64 * (w1 - w0) / std::f64::consts::TAU).ceil() as usize;
            let at = |i: usize| {
                let w = w0 + (w1 - w0) * i as f64 / count as f64;
                placed.transform_point2(DVec2::new(w.cos(), w.sin()))
            };
            for i in 0..count {
                pieces.push(DxfPiece {
                    a: at(i),
                    b: at(i + 1),
                    arc: None,
                });
            }
            return;
        }
        match ellipse_piece(placed, w0, w1) {
            Ok(piece) => pieces.push(piece),
            Err(whole) => ellipses.push(whole),
        }
    };
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
        E::Circle(c) => {
            let own = DAffine2::from_scale_angle_translation(
                DVec2::splat(c.radius),
                0.0,
                DVec2::new(c.center.x, c.center.y),
            );
            curve(own, 0.0, std::f64::consts::TAU, c.radius);
        }
        E::Arc(a) => {
            let own = DAffine2::from_scale_angle_translation(
                DVec2::splat(a.radius),
                0.0,
                DVec2::new(a.center.x, a.center.y),
            );
            curve(
                own,
                a.start_angle.to_radians(),
                a.end_angle.to_radians(),
                a.radius,
            );
        }
        E::Ellipse(el) if !crate::mutant::active("dxf_ellipses_dropped") => {
            let major = DVec2::new(el.major_axis.x, el.major_axis.y);
            let own = DAffine2::from_mat2_translation(
                DMat2::from_cols(major, major.perp() * el.minor_axis_ratio),
                DVec2::new(el.center.x, el.center.y),
            );
            curve(own, el.start_parameter, el.end_parameter, major.length());
        }
        _ => return false,
    }
    true
}

/// Reads `bytes` (a DXF file) and keeps `layer` (all when empty), its
/// curves cut by `cut` (see [`Cut`]).
pub fn read(
    bytes: &[u8],
    layer: &str,
    origin: DVec2,
    scale: f64,
    cut: Cut,
) -> Result<Drawing, String> {
    let mut reader = std::io::Cursor::new(bytes);
    let d = dxf::Drawing::load(&mut reader).map_err(|e| e.to_string())?;
    // (p − origin) · scale.
    let place = DAffine2::from_scale(DVec2::splat(scale)) * DAffine2::from_translation(-origin);
    let mut out = Drawing::default();
    let mut pieces: Vec<DxfPiece> = Vec::new();
    let mut skipped: HashMap<String, usize> = HashMap::new();
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
            let m = DAffine2::from_translation(
                place.transform_point2(DVec2::new(ins.location.x, ins.location.y)),
            ) * DAffine2::from_mat2(
                place.matrix2
                    * DMat2::from_angle(ins.rotation.to_radians())
                    * DMat2::from_diagonal(DVec2::new(ins.x_scale_factor, ins.y_scale_factor)),
            );
            for be in &block.entities {
                if !entity_pieces(&be.specific, m, (cut, 1.0), &mut pieces, &mut out.ellipses) {
                    *skipped.entry(kind_name(&be.specific)).or_default() += 1;
                }
            }
            continue;
        }
        if !entity_pieces(
            &e.specific,
            place,
            (cut, scale),
            &mut pieces,
            &mut out.ellipses,
        ) {
            *skipped.entry(kind_name(&e.specific)).or_default() += 1;
        }
        if pieces.len() > MAX_DXF_PIECES {
            return Err(format!("more than {MAX_DXF_PIECES} pieces"));
        }
    }
    out.skipped = skipped.into_iter().collect();
    out.skipped.sort();
    join(pieces, &mut out);
    if out.paths.len() + out.ellipses.len() > MAX_PATHS {
        return Err(format!(
            "more than {MAX_PATHS} closed paths, circles and ellipses"
        ));
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
/// does: while some piece has an end no other piece left reaches (the
/// lowest-numbered such piece, its first such end), the chain from there
/// is an open path; then each piece left, lowest first, starts a chain
/// followed until no piece goes on. At a point the piece taken next is
/// the lowest-numbered one left.
fn join(pieces: Vec<DxfPiece>, out: &mut Drawing) {
    let grid = if crate::mutant::active("dxf_fine_grid") {
        1.0 / 1048576.0
    } else {
        GRID
    };
    let cell = |p: DVec2| ((p.x / grid).round() as i64, (p.y / grid).round() as i64);
    // Points within a grid cell of each other are one point: each end's
    // key is the first point seen in its cell or the cells around it.
    let mut keys: HashMap<(i64, i64), usize> = HashMap::new();
    let mut points: Vec<DVec2> = Vec::new();
    let mut key_of = |p: DVec2| -> usize {
        let (i, j) = cell(p);
        if let Some(&k) = keys.get(&(i, j)) {
            return k;
        }
        // OpenSCAD's `Grid2d::align`: the nearest occupied neighbour cell
        // (by steps across, then the first found).
        let mut best: Option<(i64, usize)> = None;
        for di in -1..=1i64 {
            for dj in -1..=1i64 {
                if let Some(&k) = keys.get(&(i + di, j + dj)) {
                    let d = di.abs() + dj.abs();
                    if best.map_or(true, |(bd, _)| d < bd) {
                        best = Some((d, k));
                    }
                }
            }
        }
        if let Some((_, k)) = best {
            return k;
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
    // Follows a chain from piece `first`, entered at its end `from`: its
    // pieces, whether each is walked forward, and the point it stops at.
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
    let path_of = |chain: &[usize], forward: &[bool]| -> (Vec<DVec2>, Vec<Option<DxfArc>>) {
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
    // Whether piece i has a free end (no other piece left there): which.
    let free_end = |i: usize, used: &[bool]| -> Option<usize> {
        [ends[i].0, ends[i].1]
            .into_iter()
            .find(|e| at[e].iter().all(|&k| k == i || used[k]))
    };
    // Open chains. After one, only a piece at one of its points can have
    // a new free end: the scan goes back to the lowest of those.
    let mut i = 0;
    while i < pieces.len() {
        let Some(end) = (!used[i]).then(|| free_end(i, &used)).flatten() else {
            i += 1;
            continue;
        };
        let (chain, forward, last) = walk(i, end, &mut used);
        out.open_paths += 1;
        let (mut pts, mut arcs) = path_of(&chain, &forward);
        pts.push(points[last]);
        arcs.push(None);
        let touched = chain.iter().flat_map(|&k| [ends[k].0, ends[k].1]);
        let back = touched
            .flat_map(|p| at[&p].iter().copied())
            .filter(|&k| !used[k])
            .min();
        if let Some(b) = back {
            i = i.min(b);
        }
        push_path(out, pts, arcs);
    }
    // OpenSCAD turns the closed paths round (`fixup_path_direction`) only
    // when there are no open ones (it stops at the first open path).
    let turn = out.open_paths == 0;
    for i in 0..pieces.len() {
        if used[i] {
            continue;
        }
        let start = ends[i].0;
        let (chain, forward, last) = walk(i, start, &mut used);
        let (mut pts, mut arcs) = path_of(&chain, &forward);
        if last != start {
            // OpenSCAD keeps it, closed by a straight edge, without its
            // first point (`toPolygon2d`) — the one it ends at, where it
            // was turned round first.
            out.open_paths += 1;
            pts.push(points[last]);
            if turn && turned(&pts) {
                pts.pop();
                arcs.pop();
            } else {
                pts.remove(0);
                arcs.remove(0);
            }
            arcs.push(None);
        }
        push_path(out, pts, arcs);
    }
}

/// Whether OpenSCAD's `fixup_path_direction` reverses a closed path with
/// these points (its first and last the ends of its walk): at the first
/// point of least x, the directions back to the point before it and on to
/// the one after it compared by `atan2(dx, dy)` (x first, as OpenSCAD
/// writes it).
fn turned(pts: &[DVec2]) -> bool {
    let n = pts.len();
    let mut b = 0;
    for (j, p) in pts.iter().enumerate() {
        if p.x < pts[b].x {
            b = j;
        }
    }
    let a = if b == 0 { n - 2 } else { b - 1 };
    let c = if b == n - 1 { 1 } else { b + 1 };
    let (u, v) = (pts[a] - pts[b], pts[c] - pts[b]);
    u.x.atan2(u.y) < v.x.atan2(v.y)
}

/// Keeps a path that holds an area: three points, or an arc; a single arc
/// closing on itself is a whole ellipse.
fn push_path(out: &mut Drawing, pts: Vec<DVec2>, arcs: Vec<Option<DxfArc>>) {
    if pts.len() >= 3 || pts.len() == 2 && arcs.iter().any(|a| a.is_some()) {
        out.paths.push(DxfPath { pts, arcs });
    } else if let [Some(a)] = arcs[..] {
        out.ellipses.push(a.ellipse);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_arc_wraps_past_zero_degrees() {
        let circle = DAffine2::from_scale(DVec2::splat(2.0));
        let (w0, w1) = (270f64.to_radians(), 450f64.to_radians());
        let p = ellipse_piece(circle, w0, w1).ok().unwrap();
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
            let _ = read(&bytes[..cut], "", DVec2::ZERO, 1.0, &|_| None);
        }
        let mut seed = 7u64;
        for _ in 0..300 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let mut b = bytes.clone();
            let i = (seed >> 20) as usize % b.len();
            b[i] = (seed >> 8) as u8;
            let _ = read(&b, "body", DVec2::ZERO, 1.0, &|_| Some(7));
        }
    }
}
