//! The edges a region's lines of one family can cross, found once.
//!
//! A view's rays meet a prism's plane region along lines of one family: a
//! perspective camera's all pass through its eye (a pencil of lines
//! through one point), a directional light's shadow rays and an
//! orthographic camera's are all parallel. Each family is one parameter
//! of lines: the slope about a fixed axis for lines through a point, the
//! offset for parallel ones. Along it, each edge can only be crossed by the
//! lines whose parameter lies between its points' (ends and control
//! points, whose hull holds it), so the parameter's axis, cut at every
//! edge's least and greatest value, gives for each piece the short list of
//! edges a line in it may cross.
//!
//! A line of the family is then tested against its piece's edges only, by
//! the same code as against every edge ([`super::Region::crossings_between`]):
//! an edge left out has every point on one side of the line by a margin
//! far above the rounding of the side test (1e-9 of the terms' size
//! against their ~1e-16), so the whole-line test would have passed over it
//! too, and the crossings — found by the same arithmetic, then sorted — are
//! the same. A line within that margin of a cut between pieces gets `None`,
//! and the caller tests every edge.

use super::{Ctrl, Region};
use glam::DVec2;

/// The family: through a point (with the axis slopes are taken about), or
/// parallel to a direction.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Family {
    /// Lines through `at`; a point q has slope (q − at)·r⊥ / (q − at)·r,
    /// every point of the region lying ahead along `r`. `spread` is at
    /// least 1 and the coordinates' size (the region's and `at`'s) over
    /// the nearest point's distance from `at`: how much larger than a
    /// slope's the rounding of a side test may be.
    Through { at: DVec2, r: DVec2, spread: f64 },
    /// Lines along `dir`; a point q has offset q·dir⊥. `size` is the
    /// largest coordinate of the region's points.
    Along { dir: DVec2, size: f64 },
}

/// The least a point of the region (or a line's direction) may lie ahead
/// along the axis, as a share of its distance from the pencil's point:
/// slopes stay below 10, so a side's value is at least a hundredth of its
/// terms' size times the slopes' difference.
const AHEAD: f64 = 0.1;

/// The most edge entries a pencil keeps, per edge: beyond it (an outline
/// whose lines of the family each cross a large share of its edges) it is
/// not worth its memory.
const LIST_PER_EDGE: usize = 64;

/// The pieces of a line family's parameter, each with the edges its lines
/// may cross.
#[derive(Clone, Debug, PartialEq)]
pub struct Pencil {
    family: Family,
    /// The cuts between pieces, increasing; piece k lies between cuts k − 1
    /// and k (unbounded at the ends).
    cuts: Vec<f64>,
    /// Piece k's edges: `edges[starts[k]..starts[k + 1]]`.
    starts: Vec<u32>,
    edges: Vec<u32>,
}

impl Pencil {
    /// The pencil of lines through `at`, or `None` where the region does
    /// not lie ahead of it (`at` within or near its box).
    pub fn through(region: &Region, at: DVec2) -> Option<Pencil> {
        let r = (0.5 * (region.lo + region.hi) - at).try_normalize()?;
        let (mut nearest, mut size) = (f64::INFINITY, at.abs().max_element());
        for q in points(region) {
            let v = q - at;
            // (NaN, too, is not ahead.)
            let ahead = v.dot(r) >= AHEAD * v.length();
            if !ahead {
                return None;
            }
            nearest = nearest.min(v.length());
            size = size.max(q.abs().max_element());
        }
        let spread = (2.0 * size / nearest).max(1.0);
        if !spread.is_finite() {
            return None;
        }
        Pencil::build(region, Family::Through { at, r, spread })
    }

    /// The lines along `dir` (not zero).
    pub fn along(region: &Region, dir: DVec2) -> Option<Pencil> {
        if dir == DVec2::ZERO || !dir.is_finite() {
            return None;
        }
        let size = points(region).fold(0.0f64, |m, q| m.max(q.abs().max_element()));
        Pencil::build(region, Family::Along { dir, size })
    }

    fn param(&self, q: DVec2) -> f64 {
        match self.family {
            Family::Through { at, r, .. } => {
                let v = q - at;
                v.dot(r.perp()) / v.dot(r)
            }
            Family::Along { dir, .. } => q.dot(dir.perp()),
        }
    }

    fn build(region: &Region, family: Family) -> Option<Pencil> {
        let mut p = Pencil {
            family,
            cuts: Vec::new(),
            starts: Vec::new(),
            edges: Vec::new(),
        };
        let ranges: Vec<(f64, f64)> = (region.edges.iter().zip(&region.ctrl))
            .map(|(&(a, b), c)| {
                let ends = [a, b];
                let pts = ends.into_iter().chain(c.points());
                pts.map(|q| p.param(q))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                        (lo.min(s), hi.max(s))
                    })
            })
            .collect();
        if ranges
            .iter()
            .any(|&(lo, hi)| !(lo.is_finite() && hi.is_finite()))
        {
            return None;
        }
        p.cuts = ranges.iter().flat_map(|&(lo, hi)| [lo, hi]).collect();
        p.cuts.sort_unstable_by(f64::total_cmp);
        p.cuts.dedup();
        // An edge from cut i to cut j is in pieces i + 1 to j (those
        // between its least and greatest values); none if it is one point.
        let at = |v: f64| p.cuts.partition_point(|&c| c < v);
        let spans: Vec<(usize, usize)> = ranges
            .iter()
            .map(|&(lo, hi)| (at(lo) + 1, at(hi)))
            .collect();
        let total: usize = spans.iter().map(|&(i, j)| j + 1 - i).sum();
        if total > LIST_PER_EDGE * region.edges.len() {
            return None;
        }
        let pieces = p.cuts.len() + 1;
        let mut count = vec![0u32; pieces];
        for &(i, j) in &spans {
            for c in &mut count[i..j + 1] {
                *c += 1;
            }
        }
        // Starts by running sums; then each edge written at its pieces'
        // next places, in edge order.
        p.starts = std::iter::once(0)
            .chain(count.iter().scan(0u32, |sum, &c| {
                *sum += c;
                Some(*sum)
            }))
            .collect();
        let mut next = p.starts.clone();
        p.edges = vec![0; total];
        for (e, &(i, j)) in spans.iter().enumerate() {
            for at in &mut next[i..j + 1] {
                p.edges[*at as usize] = e as u32;
                *at += 1;
            }
        }
        Some(p)
    }

    /// The edges the line `o + s·d` may cross, if it is of this family and
    /// clear of the cuts between pieces by the margin.
    #[inline]
    pub fn edges(&self, o: DVec2, d: DVec2) -> Option<&[u32]> {
        let (s, tol) = match self.family {
            Family::Through { at, r, spread } => {
                if o != at {
                    return None;
                }
                let ahead = d.dot(r);
                // (Squared: no square root. Where the two forms round
                // apart the line is at the margin, and either answer
                // gives the same crossings.)
                if ahead * ahead < AHEAD * AHEAD * d.length_squared() {
                    return None;
                }
                let s = d.dot(r.perp()) / ahead;
                (s, 1e-9 * (1.0 + s.abs()) * spread)
            }
            Family::Along { dir, size } => {
                if d != dir {
                    return None;
                }
                let n = dir.perp();
                let s = o.dot(n);
                let tol = 1e-9 * (n.x.abs() + n.y.abs()) * (size + o.abs().max_element());
                (s, tol)
            }
        };
        // Piece k: cuts[k − 1] <= s < cuts[k].
        let k = self.cuts.partition_point(|&c| c <= s);
        let clear_left = k == 0 || s - self.cuts[k - 1] > tol;
        let clear_right = k == self.cuts.len() || self.cuts[k] - s > tol;
        if !(clear_left && clear_right && s.is_finite()) {
            return None;
        }
        let (a, b) = (self.starts[k] as usize, self.starts[k + 1] as usize);
        Some(&self.edges[a..b])
    }
}

/// Every point of the region's edges: ends and control points.
fn points(region: &Region) -> impl Iterator<Item = DVec2> + '_ {
    (region.edges.iter().zip(&region.ctrl))
        .flat_map(|(&(a, _), c): (&(DVec2, DVec2), &Ctrl)| std::iter::once(a).chain(c.points()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::tests::uniform;
    use crate::plane::Outlines;

    /// A 240-point wavy ring with a curved hole (an edge tree), and a
    /// glyph-sized loop of lines and curves (no tree).
    fn regions() -> Vec<Region> {
        let (_, ring) = crate::plane::tests::wavy_ring();
        let glyph: Vec<DVec2> = [(0.0, 0.0), (2.0, 0.0), (2.5, 3.0), (1.0, 4.0), (0.2, 3.0)]
            .map(|(x, y)| DVec2::new(x, y))
            .to_vec();
        let gctrl = vec![
            Ctrl::Line,
            Ctrl::Quad(DVec2::new(3.5, 1.0)),
            Ctrl::Quad(DVec2::new(2.5, 4.5)),
            Ctrl::Cubic(DVec2::new(0.5, 4.5), DVec2::new(-0.5, 3.5)),
            Ctrl::Line,
        ];
        let small = Region::new(Outlines {
            loops: vec![
                glyph,
                vec![
                    DVec2::new(0.8, 1.0),
                    DVec2::new(1.5, 1.0),
                    DVec2::new(1.2, 2.0),
                ],
            ],
            ctrl: vec![gctrl, vec![Ctrl::Line; 3]],
        });
        assert!(small.tree.is_none());
        vec![ring, small]
    }

    #[test]
    fn a_pencils_edges_give_the_crossings_every_edge_gives() {
        let mut next = uniform(5);
        for r in regions() {
            let pts: Vec<DVec2> = r.edges.iter().map(|&(a, _)| a).collect();
            let centre = 0.5 * (r.lo + r.hi);
            let size = (r.hi - r.lo).max_element();
            // Lines through a point at random, and how many got a piece.
            let (mut lines, mut used) = (0, 0);
            for trial in 0..40 {
                let far = [1.0, 1.0, 1e6][trial % 3];
                let a = next() * std::f64::consts::TAU;
                let unit = DVec2::new(a.cos(), a.sin());
                let through = trial % 2 == 0;
                let at = centre + unit * size * (1.5 + 20.0 * next()) + DVec2::splat(far - 1.0);
                let pencil = if through {
                    Pencil::through(&r, at)
                } else {
                    Pencil::along(&r, unit * (0.5 + next()))
                };
                let Some(p) = pencil else {
                    assert!(through && far > 1.0, "no pencil: trial {trial}");
                    continue;
                };
                for i in 0..300 {
                    // A point of the region's box, or a vertex, or a hair
                    // beside one: the line of the family through it.
                    let mut q = r.lo + (r.hi - r.lo) * DVec2::new(next(), next());
                    if i % 3 == 1 {
                        q = pts[i % pts.len()];
                    } else if i % 3 == 2 {
                        q = pts[i % pts.len()] + DVec2::new(next() - 0.5, next() - 0.5) * 1e-12;
                    }
                    let (o, d) = match p.family {
                        Family::Through { at, .. } => (at, (q - at) * (0.25 + next())),
                        Family::Along { dir, .. } => (q - dir * (10.0 * next()), dir),
                    };
                    let got = p.edges(o, d);
                    if i % 3 == 0 {
                        lines += 1;
                        used += got.is_some() as usize;
                    }
                    if let Some(ids) = got {
                        assert!(ids.len() < r.edges.len() || r.edges.len() < 8);
                        let mut got = crate::plane::Cuts::new();
                        let whole = (f64::NEG_INFINITY, f64::INFINITY);
                        let odd = r.crossings_between(Some(ids), o, d, whole, &mut got);
                        assert_eq!(
                            (got, odd),
                            (r.crossings(o, d), false),
                            "trial {trial}, line {i}: o {o:?} d {d:?}"
                        );
                    }
                }
            }
            // Nearly every line at random is answered from a piece (those
            // through or a hair beside a vertex need not be).
            assert!(used * 100 > 95 * lines, "{used} of {lines}");
        }
    }

    #[test]
    fn a_line_not_of_the_family_gets_no_piece() {
        let r = &regions()[1];
        let at = DVec2::new(-20.0, -5.0);
        let p = Pencil::through(r, at).unwrap();
        assert!(p.edges(at, DVec2::new(1.0, 0.3)).is_some());
        assert!(p
            .edges(at + DVec2::new(0.0, 1e-12), DVec2::new(1.0, 0.3))
            .is_none());
        let dir = DVec2::new(0.3, 1.0);
        let p = Pencil::along(r, dir).unwrap();
        assert!(p.edges(DVec2::new(0.9, -3.0), dir).is_some());
        assert!(p.edges(DVec2::new(0.9, -3.0), dir * 2.0).is_none());
        // Within the region's box no pencil through a point is made.
        assert!(Pencil::through(r, DVec2::new(1.0, 2.0)).is_none());
    }
}
