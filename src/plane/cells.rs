//! A region's cells: a grid over its box, each cell with the edges that
//! pass through it and one point of it known to be inside or outside.
//!
//! A ray meets a thin prism (a sign, a label, a gear's plate) along a short
//! piece of its line, between the slab's caps; the spans there need the
//! crossings on that piece and whether its first point is inside. The
//! line's own crossings before the piece answer the second (what
//! [`super::Region::crossings_between`] counts), but they are as many as
//! the outline's edges the whole line passes. Here the piece's first point
//! P takes the answer of its cell's point R, changed by the crossings of
//! the segment R–P, which can only be the cell's own edges; and the
//! crossings on the piece are those of the edges of the few cells its box
//! covers, found by the same arithmetic as along the whole line, so the
//! same places, sorted the same way.
//!
//! Each edge is listed in every cell it passes within a margin of (a
//! straight edge by its path through each row of cells, a curve by the box
//! of its control points, which holds it), the margin far above the
//! rounding of a crossing (1e-9 of the coordinates' size against their
//! ~1e-16), so that no edge a piece or a segment R–P may cross, rounding
//! included, is left out. A cell's point is its centre, or another of a
//! few points of it, at least the margin from every edge: there the
//! crossings of any line through it are on the right side of it, so its
//! answer is the even-odd rule's. A cell none of whose points is that far
//! from its edges has none, and a piece beginning there, or longer than a
//! few cells, is left to the whole line.

use super::{edge_boxes, segment_distance, window_crossings, Ctrl, Cuts, Region};
use glam::DVec2;

/// The cells a region has about this many of per edge.
const CELLS_PER_EDGE: usize = 2;

/// The most cells a grid has along one axis.
const MOST_ALONG: usize = 2048;

/// The most cells a piece's box may cover for the piece to be answered
/// here.
const MOST_COVERED: usize = 16;

/// A region of at most this many edges has no cells.
const MOST_SCANNED: usize = 32;

/// The margin, as a share of the coordinates' size.
const MARGIN: f64 = 1e-9;

#[derive(Clone, Debug)]
pub struct Cells {
    /// The grid's corner, its cells' size and their number along x and y.
    lo: DVec2,
    size: DVec2,
    nx: usize,
    ny: usize,
    /// Cell (i, j) is number j·nx + i; its edges are
    /// `edges[starts[c]..starts[c + 1]]`, ascending.
    starts: Vec<u32>,
    edges: Vec<u32>,
    /// Each cell's point and whether it is inside; `None` where no point
    /// of the cell is far enough from its edges.
    known: Vec<Option<(DVec2, bool)>>,
    margin: f64,
}

impl Cells {
    /// The cells of `region`, or `None` for a region with no extent or
    /// whose cells would be too small for the margin.
    pub fn new(region: &Region) -> Option<Cells> {
        let n = region.edges.len();
        if n == 0 {
            return None;
        }
        // The box of every edge's control points, which holds the region.
        let boxes = edge_boxes(&region.edges, &region.ctrl);
        let (lo, hi) = boxes.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(l, h), &(a, b)| (l.min(a), h.max(b)),
        );
        let extent = hi - lo;
        let scale = lo.abs().max(hi.abs()).max_element();
        let margin = MARGIN * scale;
        if extent.min_element().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            || !scale.is_finite()
        {
            return None;
        }
        // About CELLS_PER_EDGE·n cells, as square as the box allows.
        let want = (CELLS_PER_EDGE * n) as f64;
        let nx = ((want * extent.x / extent.y).sqrt().ceil() as usize).clamp(1, MOST_ALONG);
        let ny = ((want / nx as f64).ceil() as usize).clamp(1, MOST_ALONG);
        let size = extent / DVec2::new(nx as f64, ny as f64);
        if size.min_element() <= 1e3 * margin {
            return None;
        }
        let mut cells = Cells {
            lo,
            size,
            nx,
            ny,
            starts: Vec::new(),
            edges: Vec::new(),
            known: Vec::new(),
            margin,
        };
        // (cell, edge) for every cell an edge passes within the margin of.
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (k, (&(a, b), c)) in region.edges.iter().zip(&region.ctrl).enumerate() {
            let (blo, bhi) = boxes[k];
            let (j0, j1) = cells.rows(blo.y - margin, bhi.y + margin);
            for j in j0..=j1 {
                // The edge's x range within the row (grown by the margin).
                let (x0, x1) = if *c == Ctrl::Line && a.y != b.y {
                    let y_lo = (lo.y + j as f64 * size.y - margin).max(blo.y);
                    let y_hi = (lo.y + (j + 1) as f64 * size.y + margin).min(bhi.y);
                    let at = |y: f64| a.x + (b.x - a.x) * ((y - a.y) / (b.y - a.y));
                    let (p, q) = (at(y_lo), at(y_hi));
                    (p.min(q).max(blo.x), p.max(q).min(bhi.x))
                } else {
                    (blo.x, bhi.x)
                };
                let (i0, i1) = cells.columns(x0 - margin, x1 + margin);
                for i in i0..=i1 {
                    pairs.push(((j * nx + i) as u32, k as u32));
                }
            }
        }
        pairs.sort_unstable();
        cells.starts = vec![0; nx * ny + 1];
        for &(c, _) in &pairs {
            cells.starts[c as usize + 1] += 1;
        }
        for c in 0..nx * ny {
            cells.starts[c + 1] += cells.starts[c];
        }
        cells.edges = pairs.into_iter().map(|(_, k)| k).collect();
        // Each row's centres by the crossings of the line through them
        // along x, counted up to each (one line a row, not one a cell).
        cells.known = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            let o = DVec2::new(lo.x, lo.y + (j as f64 + 0.5) * size.y);
            let cuts = region.crossings(o, DVec2::X);
            let mut before = 0;
            for i in 0..nx {
                let x = (i as f64 + 0.5) * size.x;
                while before < cuts.len() && cuts[before].0 < x {
                    before += 1;
                }
                let known = cells.point(region, j * nx + i, before % 2 == 1);
                cells.known.push(known);
            }
        }
        Some(cells)
    }

    /// The rows of cells from height `y0` to `y1`, clamped to the grid.
    fn rows(&self, y0: f64, y1: f64) -> (usize, usize) {
        let at = |y| along(y, self.lo.y, self.size.y, self.ny);
        (at(y0), at(y1))
    }

    /// The columns of cells from `x0` to `x1`, clamped to the grid.
    fn columns(&self, x0: f64, x1: f64) -> (usize, usize) {
        let at = |x| along(x, self.lo.x, self.size.x, self.nx);
        (at(x0), at(x1))
    }

    fn cell_edges(&self, c: usize) -> &[u32] {
        &self.edges[self.starts[c] as usize..self.starts[c + 1] as usize]
    }

    /// Cell `c`'s point and whether it is inside: the first of its centre
    /// (inside if `centre_inside`) and four points about it that lies at
    /// least the margin from each of the cell's edges (a curve by the box
    /// of its control points).
    fn point(&self, region: &Region, c: usize, centre_inside: bool) -> Option<(DVec2, bool)> {
        let (i, j) = (c % self.nx, c / self.nx);
        let corner = self.lo + DVec2::new(i as f64, j as f64) * self.size;
        let clear = |p: DVec2| {
            self.cell_edges(c).iter().all(|&k| {
                let (a, b) = region.edges[k as usize];
                let far = match region.ctrl[k as usize] {
                    Ctrl::Line => segment_distance(a - p, b - p),
                    ctrl => {
                        let (blo, bhi) = ctrl.bounds(a, b);
                        (blo - p).max(p - bhi).max(DVec2::ZERO).length()
                    }
                };
                far > self.margin
            })
        };
        let centre = corner + 0.5 * self.size;
        if clear(centre) {
            return Some((centre, centre_inside));
        }
        [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)]
            .into_iter()
            .map(|(u, v)| corner + DVec2::new(u, v) * self.size)
            .find(|&p| clear(p))
            .map(|p| (p, region.contains(p)))
    }

    /// The crossings of the line `o + s·d` with `lo ≤ s ≤ hi`, pushed onto
    /// `cuts` and sorted as [`Region::crossings_between`] gives them, and
    /// whether the point at `lo` is inside; `None` (nothing pushed) where
    /// the piece is unbounded, covers too many cells or begins in a cell
    /// with no point.
    pub fn crossings_between(
        &self,
        region: &Region,
        o: DVec2,
        d: DVec2,
        (lo, hi): (f64, f64),
        cuts: &mut Cuts,
    ) -> Option<bool> {
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        let (p, q) = (o + lo * d, o + hi * d);
        let (i0, i1) = self.columns(p.x.min(q.x) - self.margin, p.x.max(q.x) + self.margin);
        let (j0, j1) = self.rows(p.y.min(q.y) - self.margin, p.y.max(q.y) + self.margin);
        if (i1 - i0 + 1) * (j1 - j0 + 1) > MOST_COVERED {
            return None;
        }
        let edge = |k: &u32| region.edge(*k);
        // Whether P is inside: beyond the box by more than the margin, not;
        // else its cell's answer, changed by each crossing of R–P.
        let grid_hi = self.lo + self.size * DVec2::new(self.nx as f64, self.ny as f64);
        let beyond = (self.lo - p).max(p - grid_hi).max_element();
        let inside = if beyond > self.margin {
            false
        } else {
            let (ci, cj) = (self.columns(p.x, p.x).0, self.rows(p.y, p.y).0);
            let c = cj * self.nx + ci;
            let (r, r_inside) = self.known[c]?;
            let mut odd = false;
            if p != r {
                let near = self.cell_edges(c).iter().map(edge);
                window_crossings(near, r, p - r, 0.0, 1.0, |_, _| odd = !odd);
            }
            r_inside != odd
        };
        // The edges of the cells the piece's box covers, each once.
        let mut ids: smallvec::SmallVec<[u32; 32]> = smallvec::SmallVec::new();
        for j in j0..=j1 {
            for i in i0..=i1 {
                ids.extend_from_slice(self.cell_edges(j * self.nx + i));
            }
        }
        if (i0, j0) != (i1, j1) {
            ids.sort_unstable();
            ids.dedup();
        }
        let start = cuts.len();
        window_crossings(ids.iter().map(edge), o, d, lo, hi, |s, k| cuts.push((s, k)));
        cuts[start..].sort_by(super::by_place);
        Some(inside)
    }
}

/// The cell of `n` (from `lo`, each `size` long) that `v` falls in,
/// clamped to them.
fn along(v: f64, lo: f64, size: f64, n: usize) -> usize {
    ((v - lo) / size).floor().clamp(0.0, (n - 1) as f64) as usize
}

/// A region's cells, made when a ray first asks for them: a cache, so that
/// two regions are equal whether or not either has made its cells.
#[derive(Clone, Debug, Default)]
pub struct CellCache(std::sync::OnceLock<Option<Cells>>);

impl PartialEq for CellCache {
    fn eq(&self, _: &CellCache) -> bool {
        true
    }
}

impl CellCache {
    /// The cells of `region` (whose cache this is): made the first time,
    /// for a region of more than [`MOST_SCANNED`] edges.
    pub fn get(&self, region: &Region) -> Option<&Cells> {
        self.0
            .get_or_init(|| {
                (region.edges.len() > MOST_SCANNED)
                    .then(|| Cells::new(region))
                    .flatten()
            })
            .as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::tests::{flower, uniform, wavy_ring};
    use crate::plane::Outlines;

    /// A short piece's crossings and first point's side, by its cells, are
    /// the whole line's, to the bit: on the flower (quadratic and cubic
    /// curves), the wavy ring and a 600-edge star, for pieces at random
    /// (in, across and beyond the box; some through the points that
    /// define the edges), of lengths from a thousandth of a cell to a few
    /// cells. Most short pieces are answered by the cells.
    #[test]
    fn a_short_piece_has_the_whole_lines_crossings() {
        let mut next = uniform(11);
        let star = Region::new(Outlines::polygons(vec![(0..600)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 600.0;
                DVec2::new(a.cos(), a.sin()) * (30.0 + 7.0 * (37.0 * a).sin())
            })
            .collect()]));
        let (_, ring) = wavy_ring();
        for r in [flower(), ring, star] {
            let cells = Cells::new(&r).expect("cells");
            let pts: Vec<DVec2> = (r.edges.iter().zip(&r.ctrl))
                .flat_map(|(&(a, _), c)| std::iter::once(a).chain(c.points()))
                .collect();
            let (mut asked, mut answered) = (0, 0);
            for i in 0..20000 {
                let start = if i % 3 == 0 {
                    pts[i % pts.len()] + (DVec2::new(next(), next()) - 0.5) * cells.size * 0.01
                } else {
                    r.lo + (r.hi - r.lo) * (DVec2::new(next(), next()) * 1.2 - 0.1)
                };
                let angle = next() * std::f64::consts::TAU;
                let dir = DVec2::new(angle.cos(), angle.sin());
                let length = cells.size.max_element() * 10f64.powf(3.0 * next() - 2.5);
                let speed = 0.1 + 10.0 * next();
                let o = start - dir * (next() * 50.0);
                let d = dir * speed;
                let lo = (start - o).dot(d) / d.length_squared();
                let hi = lo + length / speed;
                let mut got = Cuts::new();
                let Some(inside) = cells.crossings_between(&r, o, d, (lo, hi), &mut got) else {
                    assert!(got.is_empty());
                    asked += 1;
                    continue;
                };
                let mut want = Cuts::new();
                let odd = r.crossings_between(None, o, d, (lo, hi), &mut want);
                assert_eq!(
                    got.to_vec(),
                    want.to_vec(),
                    "piece {i}: {o:?} + s {d:?} in [{lo}, {hi}]"
                );
                assert_eq!(inside, odd, "piece {i}: {o:?} + s {d:?} in [{lo}, {hi}]");
                asked += 1;
                answered += 1;
            }
            assert!(answered * 10 > asked * 7, "{answered} of {asked} answered");
        }
    }

    /// A cell's point is at least the margin from every edge, and its side
    /// is the region's own inside test's.
    #[test]
    fn each_cells_point_is_clear_and_on_its_side() {
        for r in [flower(), wavy_ring().1] {
            let cells = Cells::new(&r).expect("cells");
            let known = cells.known.iter().flatten().count();
            assert!(
                known * 10 > cells.known.len() * 8,
                "{known} of {}",
                cells.known.len()
            );
            for &(p, inside) in cells.known.iter().flatten() {
                assert_eq!(inside, r.contains(p), "{p:?}");
                for (&(a, b), c) in r.edges.iter().zip(&r.ctrl) {
                    let (blo, bhi) = c.bounds(a, b);
                    let boxed = (blo - p).max(p - bhi).max(DVec2::ZERO).length();
                    let far = match c {
                        Ctrl::Line => segment_distance(a - p, b - p),
                        _ => boxed,
                    };
                    assert!(far > cells.margin, "{p:?} within {far} of an edge");
                }
            }
        }
    }
}
