//! Adaptive anti-aliasing: which pixels are sampled again, from the first
//! pass's pixel centres and the corners of the pixels near an edge.

use crate::geometry::coherence::coherent;
use crate::stats::Stats;
use glam::DVec3;
use rayon::prelude::*;

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
    lin: &[f32],
    w: usize,
    h: usize,
    threshold: f64,
    corner: impl Fn(u32, u32, &mut Stats) -> Option<[f64; 3]> + Sync,
    progress: &(dyn Fn(super::Progress) + Sync),
) -> (Vec<Vec<u32>>, Stats) {
    let near = edges(lin, w, h, threshold);
    let near_at = |x: usize, y: usize| x < w && y < h && near[y * w + x];
    // Each row of corners: the columns of the corners of pixels near an
    // edge (a corner is pixel (x, y)'s top left), each sampled once.
    let columns: Vec<Vec<u32>> = (0..=h)
        .into_par_iter()
        .map(|y| {
            let rows = [y.wrapping_sub(1), y];
            if !rows
                .iter()
                .any(|&r| r < h && near[r * w..][..w].contains(&true))
            {
                return Vec::new();
            }
            (0..=w)
                .filter(|&x| {
                    rows.iter()
                        .any(|&r| near_at(x, r) || near_at(x.wrapping_sub(1), r))
                })
                .map(|x| x as u32)
                .collect()
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
            (0..w)
                .filter(|&x| {
                    if !near[y * w + x] {
                        return false;
                    }
                    let mut seen = [shown_at(lin, 3 * (y * w + x)); 5];
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
                .map(|x| x as u32)
                .collect()
        })
        .collect();
    (again, stats)
}

/// The pixels near an edge: those whose colour (clamped to [0, 1], as it
/// is shown) differs from an 8-neighbour's by more than `threshold`,
/// summed over red, green and blue. A pixel whose 3×3 block holds one
/// radiance, bit for bit (most of a picture: its background, a flat
/// face), differs from no neighbour and is not measured; the rest are
/// measured as the rule says.
fn edges(lin: &[f32], w: usize, h: usize, threshold: f64) -> Vec<bool> {
    let mut near = vec![false; w * h];
    if w == 0 {
        return near;
    }
    let row = |y: usize| &lin[3 * w * y..][..3 * w];
    near.par_chunks_mut(w).enumerate().for_each(|(y, out)| {
        let (up, mid, down) = (row(y.saturating_sub(1)), row(y), row((y + 1).min(h - 1)));
        let same = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(p, q)| p.to_bits() == q.to_bits());
        // Three rows of one radiance (a band of background): no pixel in
        // the middle one is near an edge.
        if same(up, mid) && same(down, mid) && mid.chunks_exact(3).all(|p| same(p, &mid[..3])) {
            return;
        }
        // Whether the column's pixels in rows y − 1, y, y + 1 are one.
        let column: Vec<bool> = (0..w)
            .map(|x| {
                let k = 3 * x..3 * x + 3;
                same(&up[k.clone()], &mid[k.clone()]) && same(&down[k.clone()], &mid[k])
            })
            .collect();
        for (x, o) in out.iter_mut().enumerate() {
            let (l, r) = (x.saturating_sub(1), (x + 1).min(w - 1));
            let flat = column[l]
                && column[x]
                && column[r]
                && same(&mid[3 * l..3 * l + 3], &mid[3 * x..3 * x + 3])
                && same(&mid[3 * r..3 * r + 3], &mid[3 * x..3 * x + 3]);
            *o = !flat && differs_around(lin, w, h, x, y, threshold);
        }
    });
    near
}

/// Whether pixel (x, y)'s shown colour differs from an 8-neighbour's by
/// more than `threshold`.
fn differs_around(lin: &[f32], w: usize, h: usize, x: usize, y: usize, threshold: f64) -> bool {
    let c = shown_at(lin, 3 * (y * w + x));
    (y.saturating_sub(1)..(y + 2).min(h)).any(|ny| {
        (x.saturating_sub(1)..(x + 2).min(w))
            .any(|nx| differ(&c, &shown_at(lin, 3 * (ny * w + nx))) > threshold)
    })
}

/// A colour as it is shown: each value clamped to [0, 1].
pub fn shown(c: DVec3) -> [f64; 3] {
    c.to_array().map(|v| v.clamp(0.0, 1.0))
}

/// The shown colour of the radiance at `lin[i..i + 3]`.
fn shown_at(lin: &[f32], i: usize) -> [f64; 3] {
    [lin[i], lin[i + 1], lin[i + 2]].map(|v| (v as f64).clamp(0.0, 1.0))
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
    /// with values past 0 and 1, −0, NaN and near-misses of the threshold.
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
        for case in 0..60 {
            let (w, h) = (1 + (rnd() * 23.0) as usize, 1 + (rnd() * 17.0) as usize);
            let colours: Vec<[f32; 3]> = (0..4)
                .map(|_| [0; 3].map(|_| palette[(rnd() * palette.len() as f64) as usize]))
                .collect();
            let lin: Vec<f32> = (0..w * h)
                .flat_map(|_| colours[(rnd() * rnd() * 4.0) as usize])
                .collect();
            let threshold = [0.3, 0.05, 0.0][case % 3];
            let rule: Vec<bool> = (0..w * h)
                .map(|i| {
                    let (x, y) = (i % w, i / w);
                    let c = shown_at(&lin, 3 * i);
                    (y.saturating_sub(1)..(y + 2).min(h)).any(|ny| {
                        (x.saturating_sub(1)..(x + 2).min(w))
                            .any(|nx| differ(&c, &shown_at(&lin, 3 * (ny * w + nx))) > threshold)
                    })
                })
                .collect();
            assert_eq!(edges(&lin, w, h, threshold), rule, "case {case}: {w}x{h}");
        }
    }
}
