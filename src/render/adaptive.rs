//! Adaptive anti-aliasing: which pixels are sampled again, from the first
//! pass's pixel centres and the corners of the pixels near an edge.

use crate::geometry::coherence::coherent;
use crate::stats::Stats;
use glam::DVec3;
use rayon::prelude::*;
use std::ops::Range;

/// Adaptive anti-aliasing, after POV-Ray's `+AM1` and `+AM2` with
/// `+A0.3`: every pixel gets one sample at its centre. A pixel whose
/// centre colour differs from one of its eight neighbours' by more than
/// `threshold` (the sum of the absolute differences of red, green and
/// blue, shown values in [0, 1]) is near an edge; its four corners are
/// sampled (once each, shared with its neighbours). If a corner differs
/// from the centre or from another corner by more than `threshold` (or
/// gives no finite colour), an edge crosses the pixel — a straight edge
/// through a square leaves corners on both its sides — and the pixel is
/// sampled again with [`super::Settings::spp`] stratified samples, exactly the
/// samples `--spp` of that number takes there, and gets their mean; else
/// it keeps its centre's colour. Every decision depends on samples fixed
/// by the pixel coordinates only, so the image is the same for any thread
/// count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    pub threshold: f64,
}

/// POV-Ray's default `Antialias_Threshold`.
pub const ADAPTIVE_THRESHOLD: f64 = 0.3;
/// The samples of a refined pixel by default: 13 correlated
/// multi-jittered samples leave people's models' edge pixels as close to
/// their converged colours as 16 N-rooks samples did (RMS 6.61 against
/// 6.71 levels, `tools/bench/aa_error.py`), for 13/16 of the rays.
pub const ADAPTIVE_SPP: u32 = 13;

/// The pixels adaptive anti-aliasing samples again, as each row's
/// columns in ascending order, from the first pass's radiance `lin` (three
/// values a pixel, `w`×`h`, row-major) and `corner(x, y)`, the shown colour
/// at image point (x, y) (`None` where it is not finite), asked once for
/// each corner of a pixel near an edge; with the counters of those
/// samples. `progress` hears of the corners as [`super::render`]'s passes
/// tell theirs. Only the corners asked for are stored.
pub fn crossed(
    first: &FirstPass,
    threshold: f64,
    corner: impl Fn(u32, u32, &mut Stats) -> Option<[f64; 3]> + Sync,
    progress: &(dyn Fn(super::Progress) + Sync),
) -> (Vec<Vec<u32>>, Stats) {
    let h = first.h;
    let near = edges(first, threshold);
    // Each row of corners: the columns of the corners of pixels near an
    // edge (a corner is pixel (x, y)'s top left), each sampled once.
    let columns: Vec<Vec<u32>> = (0..=h)
        .into_par_iter()
        .map(|y| {
            let mut xs: Vec<u32> = [y.wrapping_sub(1), y]
                .iter()
                .filter(|&&r| r < h)
                .flat_map(|&r| near[r].iter().flat_map(|&x| [x, x + 1]))
                .collect();
            xs.sort_unstable();
            xs.dedup();
            xs
        })
        .collect();
    let count = columns.iter().map(Vec::len).sum::<usize>() as u64;
    if count == 0 {
        return (vec![Vec::new(); h], Stats::default());
    }
    progress(super::Progress::Planned(count));
    let (colours, stats) = columns
        .par_iter()
        .enumerate()
        .with_max_len(1)
        .map(|(y, xs)| {
            let mut st = Stats::default();
            let row: Vec<_> =
                coherent(|| xs.iter().map(|&x| corner(x, y as u32, &mut st)).collect());
            progress(super::Progress::Done(xs.len() as u64));
            (row, st)
        })
        .collect::<Vec<_>>()
        .into_iter()
        .fold(
            (Vec::new(), Stats::default()),
            |(mut all, mut sum), (row, st)| {
                all.push(row);
                sum.add(&st);
                (all, sum)
            },
        );
    let at = |x: usize, y: usize| {
        let k = columns[y].partition_point(|&c| (c as usize) < x);
        colours[y][k]
    };
    // Sampled again: a pixel near an edge one of whose corners differs
    // from its centre or from another corner by more than the threshold,
    // or gave no finite colour.
    let again = (0..h)
        .into_par_iter()
        .map(|y| {
            near[y]
                .iter()
                .copied()
                .filter(|&x| {
                    let x = x as usize;
                    let mut seen = [shown_of(first.at(x, y)); 5];
                    let four = [at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)];
                    for (k, c) in four.into_iter().enumerate() {
                        let Some(c) = c else { return true };
                        if seen[..=k].iter().any(|o| differ(o, &c) > threshold) {
                            return true;
                        }
                        seen[k + 1] = c;
                    }
                    false
                })
                .collect()
        })
        .collect();
    (again, stats)
}

/// The first pass's radiance, where it was cast: three `f32` a pixel of
/// `lin` (`w`×`h`, row-major), read only in each row's `cast` columns;
/// every other pixel is the `background`'s, which its row was given
/// without a ray (and whose place in `lin` is not read, so that its pages
/// are never touched).
pub struct FirstPass<'a> {
    pub lin: &'a [f32],
    pub w: usize,
    pub h: usize,
    pub cast: &'a [Range<u32>],
    pub background: [f32; 3],
}

impl FirstPass<'_> {
    /// The shown colours of row `y`'s pixels in `xs`.
    fn shown_row(&self, y: usize, xs: Range<usize>) -> Vec<[f64; 3]> {
        let c = &self.cast[y];
        let from = (c.start as usize).clamp(xs.start, xs.end);
        let to = (c.end as usize).clamp(from, xs.end);
        let bg = shown_of(self.background);
        let lin = &self.lin[3 * (y * self.w + from)..3 * (y * self.w + to)];
        let mut row = Vec::with_capacity(xs.len());
        row.resize(from - xs.start, bg);
        row.extend(lin.chunks_exact(3).map(|p| shown_of([p[0], p[1], p[2]])));
        row.resize(xs.len(), bg);
        row
    }

    /// Pixel (x, y)'s radiance.
    fn at(&self, x: usize, y: usize) -> [f32; 3] {
        if self.cast[y].contains(&(x as u32)) {
            let i = 3 * (y * self.w + x);
            [self.lin[i], self.lin[i + 1], self.lin[i + 2]]
        } else {
            self.background
        }
    }
}

/// Rows measured together, by one task: each row's colours are read once
/// for it and the rows beside it, and each pair of neighbours is measured
/// once (four pairs a pixel instead of eight neighbours).
const EDGE_ROWS: usize = 16;

/// The pixels near an edge, as each row's columns in ascending order:
/// those whose colour (clamped to [0, 1], as it is shown) differs from an
/// 8-neighbour's by more than `threshold`, summed over red, green and
/// blue (the same both ways: a − b is −(b − a) to the bit). Only the
/// columns within one pixel of a cast column of the row or of the rows
/// above and below are measured: every other pixel's 3×3 block is the
/// background's alone, one radiance bit for bit, which differs from no
/// neighbour. A pixel at the picture's side has no neighbour there.
fn edges(first: &FirstPass, threshold: f64) -> Vec<Vec<u32>> {
    let (w, h) = (first.w, first.h);
    // Row y's measured columns.
    let measured = |y: usize| {
        let rows = [y.saturating_sub(1), y, (y + 1).min(h - 1)];
        let cast = rows.map(|r| &first.cast[r]);
        let r = hull(cast.iter().map(|c| c.start as usize..c.end as usize));
        if r.is_empty() {
            return 0..0;
        }
        r.start.saturating_sub(1)..(r.end + 1).min(w)
    };
    let tasks: Vec<Vec<Vec<u32>>> = (0..h.div_ceil(EDGE_ROWS))
        .into_par_iter()
        .map(|k| {
            let (y0, y1) = (k * EDGE_ROWS, ((k + 1) * EDGE_ROWS).min(h));
            let ranges: Vec<Range<usize>> = (y0..y1).map(measured).collect();
            let Range { start: lo, end: hi } = hull(ranges.iter().cloned());
            if lo >= hi {
                return vec![Vec::new(); y1 - y0];
            }
            // The columns measured, one more on each side, of these rows
            // and the two beside them.
            let (a, b) = (lo.saturating_sub(1), (hi + 1).min(w));
            let n = b - a;
            let (r0, r1) = (y0.saturating_sub(1), (y1 + 1).min(h));
            let shown: Vec<Vec<[f64; 3]>> = (r0..r1).map(|r| first.shown_row(r, a..b)).collect();
            let mut near = vec![false; (y1 - y0) * n];
            let mut pair = |(y, j): (usize, usize), (v, i): (usize, usize)| {
                if differ(&shown[y - r0][j], &shown[v - r0][i]) > threshold {
                    for (y, j) in [(y, j), (v, i)] {
                        if (y0..y1).contains(&y) {
                            near[(y - y0) * n + j] = true;
                        }
                    }
                }
            };
            for y in r0..r1 {
                for j in 0..n {
                    // Right (within the task's rows), and the three below.
                    if j + 1 < n && (y0..y1).contains(&y) {
                        pair((y, j), (y, j + 1));
                    }
                    if y + 1 < r1 {
                        pair((y, j), (y + 1, j));
                        if j + 1 < n {
                            pair((y, j), (y + 1, j + 1));
                            pair((y, j + 1), (y + 1, j));
                        }
                    }
                }
            }
            (y0..y1)
                .zip(ranges)
                .map(|(y, r)| {
                    r.filter(|&x| near[(y - y0) * n + x - a])
                        .map(|x| x as u32)
                        .collect()
                })
                .collect()
        })
        .collect();
    tasks.into_iter().flatten().collect()
}

/// The least range holding every non-empty one of `ranges` (empty if
/// none is).
fn hull(ranges: impl Iterator<Item = Range<usize>>) -> Range<usize> {
    let (lo, hi) = ranges
        .filter(|r| !r.is_empty())
        .fold((usize::MAX, 0), |(lo, hi), r| {
            (lo.min(r.start), hi.max(r.end))
        });
    lo..hi
}

/// A colour as it is shown: each value clamped to [0, 1].
pub fn shown(c: DVec3) -> [f64; 3] {
    c.to_array().map(|v| v.clamp(0.0, 1.0))
}

/// The shown colour of a pixel's radiance.
fn shown_of(r: [f32; 3]) -> [f64; 3] {
    r.map(|v| (v as f64).clamp(0.0, 1.0))
}

/// How far two shown colours differ: the sum of the absolute differences
/// of red, green and blue.
fn differ(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`edges`] against the rule read directly — each pixel measured
    /// against each of its eight neighbours that exist — on random
    /// pictures of a few colours (runs of one radiance, as pictures have)
    /// with values past 0 and 1, −0, NaN and near-misses of the threshold,
    /// each row cast in a random range of columns (or none, or all) and
    /// the background's elsewhere; what `lin` holds outside the cast
    /// columns is a colour of its own, which must never be read.
    #[test]
    fn edges_are_the_rule() {
        let mut rnd = crate::plane::tests::uniform(7);
        let palette = [
            0.0f32,
            -0.0,
            0.5,
            0.55,
            0.8,
            1.0,
            1.7,
            -0.3,
            f32::NAN,
            0.1,
            0.4,
        ];
        for case in 0..200 {
            let (w, h) = (1 + (rnd() * 23.0) as usize, 1 + (rnd() * 17.0) as usize);
            let colours: Vec<[f32; 3]> = (0..4)
                .map(|_| [0; 3].map(|_| palette[(rnd() * palette.len() as f64) as usize]))
                .collect();
            let background = colours[(rnd() * 4.0) as usize];
            let cast: Vec<Range<u32>> = (0..h)
                .map(|_| match (rnd() * 4.0) as usize {
                    0 => 0..0,
                    1 => 0..w as u32,
                    _ => {
                        let (a, b) = ((rnd() * w as f64) as u32, (rnd() * w as f64) as u32);
                        a.min(b)..a.max(b) + 1
                    }
                })
                .collect();
            let cast_at = |x: usize, y: usize| cast[y].contains(&(x as u32));
            let shown: Vec<[f32; 3]> = (0..w * h)
                .map(|i| match cast_at(i % w, i / w) {
                    true => colours[(rnd() * rnd() * 4.0) as usize],
                    false => background,
                })
                .collect();
            let lin: Vec<f32> = (0..w * h)
                .flat_map(|i| match cast_at(i % w, i / w) {
                    true => shown[i],
                    false => [0.77, 2.0, f32::NAN],
                })
                .collect();
            let threshold = [0.3, 0.05, 0.0][case % 3];
            let rule: Vec<bool> = (0..w * h)
                .map(|i| {
                    let (x, y) = (i % w, i / w);
                    let c = shown_of(shown[i]);
                    (y.saturating_sub(1)..(y + 2).min(h)).any(|ny| {
                        (x.saturating_sub(1)..(x + 2).min(w))
                            .any(|nx| differ(&c, &shown_of(shown[ny * w + nx])) > threshold)
                    })
                })
                .collect();
            let first = FirstPass {
                lin: &lin,
                w,
                h,
                cast: &cast,
                background,
            };
            let got = edges(&first, threshold);
            assert!(got.iter().all(|xs| xs.windows(2).all(|p| p[0] < p[1])));
            let near: Vec<bool> = (0..w * h)
                .map(|i| got[i / w].contains(&((i % w) as u32)))
                .collect();
            assert_eq!(near, rule, "case {case}: {w}x{h}");
        }
    }
}
