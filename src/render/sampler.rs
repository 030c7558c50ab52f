//! Sub-pixel sample positions: correlated multi-jittered sampling
//! (Kensler, "Correlated Multi-Jittered Sampling", 2013) for any count n —
//! each sample alone in one of n rows and in one of m·k columns (m = ⌊√n⌋,
//! k = ⌈n/m⌉), and at most one in each cell of a grid of m columns and k
//! rows when n = m·k, as in a jittered grid — seeded from the pixel
//! coordinates only, so images do not depend on threads or run order.

use smallvec::SmallVec;

/// The offsets inside pixel (px, py) of its `n` samples, in [0, 1)², row
/// by row. One sample is the pixel centre.
pub fn offsets(px: u32, py: u32, n: u32) -> impl Iterator<Item = (f64, f64)> {
    let seed = hash(((py as u64) << 32) | px as u64);
    let p = seed as u32;
    let m = ((n as f64).sqrt() as u32).max(1);
    let k = n.div_ceil(m);
    // Sample r takes row r of n; its cell of the grid is (r mod m,
    // r div m), its column in that cell's band permuted per pixel: the
    // two permutations are tables of m and k entries, not 2n hashes.
    let columns: SmallVec<[u32; 16]> = (0..m)
        .map(|i| permute(i, m, p.wrapping_mul(0x68bc_21eb)))
        .collect();
    let bands: SmallVec<[u32; 16]> = (0..k)
        .map(|i| permute(i, k, p.wrapping_mul(0x02e5_be93)))
        .collect();
    (0..n).map(move |r| {
        if n <= 1 {
            return (0.5, 0.5);
        }
        let (cx, cy) = (columns[(r % m) as usize], bands[(r / m) as usize]);
        let jx = unit(hash(seed ^ (2 * r as u64 + 1)));
        let jy = unit(hash(seed ^ (2 * r as u64 + 2) << 20));
        (
            (cx as f64 + (cy as f64 + jx) / k as f64) / m as f64,
            (r as f64 + jy) / n as f64,
        )
    })
}

/// SplitMix64's finaliser: a fast, well-mixed 64-bit hash.
fn hash(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) from the top 53 bits.
fn unit(h: u64) -> f64 {
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Element `i` of a pseudo-random permutation of 0..len chosen by `seed`
/// (Kensler, "Correlated Multi-Jittered Sampling", 2013): an invertible
/// hash on the smallest power-of-two domain covering `len`, cycle-walked
/// until it lands inside 0..len.
pub fn permute(mut i: u32, len: u32, seed: u32) -> u32 {
    let mut w = len - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= seed;
        i = i.wrapping_mul(0xe170_893d);
        i ^= seed >> 16;
        i ^= (i & w) >> 4;
        i ^= seed >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= seed >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | seed >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < len {
            break;
        }
    }
    (i + seed) % len
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permute_is_a_permutation_for_every_length() {
        for len in 1..200 {
            for seed in [0u32, 1, 0xdead_beef, 12345] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let j = permute(i, len, seed) as usize;
                    assert!(!seen[j], "len {len} seed {seed}: {j} twice");
                    seen[j] = true;
                }
            }
        }
    }

    #[test]
    fn samples_are_stratified_in_rows_columns_and_cells() {
        for n in 2..=64u32 {
            let m = (n as f64).sqrt() as u32;
            let k = n.div_ceil(m);
            for (px, py) in [(7, 9), (0, 0), (799, 599)] {
                let mut rows = vec![0; n as usize];
                let mut columns = vec![0; (m * k) as usize];
                let mut cells = vec![0; (m * k) as usize];
                assert_eq!(offsets(px, py, n).count(), n as usize);
                for (x, y) in offsets(px, py, n) {
                    assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
                    rows[(y * n as f64) as usize] += 1;
                    columns[(x * (m * k) as f64) as usize] += 1;
                    let cell = (y * k as f64) as u32 * m + (x * m as f64) as u32;
                    cells[cell as usize] += 1;
                }
                assert!(rows.iter().all(|&c| c == 1), "n {n}: rows {rows:?}");
                assert!(columns.iter().all(|&c| c <= 1), "n {n}: {columns:?}");
                if n == m * k {
                    assert!(cells.iter().all(|&c| c == 1), "n {n}: cells {cells:?}");
                }
            }
        }
    }

    #[test]
    fn one_sample_is_the_pixel_centre() {
        for (px, py) in [(0, 0), (7, 3), (4000, 12)] {
            assert!(offsets(px, py, 1).eq([(0.5, 0.5)]));
        }
    }

    #[test]
    fn samples_depend_on_the_pixel() {
        // Over a 16×16 block, the column stratum of the first sample (of 4,
        // the one in the top row) and its jitter vary from pixel to pixel:
        // every stratum is used, and no two pixels share an offset (a
        // constant pattern would alias).
        let mut strata = [0u32; 4];
        let mut seen = Vec::new();
        for py in 0..16 {
            for px in 0..16 {
                let (x, y) = offsets(px, py, 4).next().unwrap();
                strata[(x * 4.0) as usize] += 1;
                seen.push((x.to_bits(), y.to_bits()));
            }
        }
        assert!(strata.iter().all(|&c| c >= 32), "{strata:?}");
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 256);
    }
}
