//! Sub-pixel sample positions: N-rooks (Latin hypercube) stratification
//! with jitter — sample s lies in column stratum s and row stratum π(s) of
//! an N×N grid over the pixel, π a permutation — seeded from the pixel
//! coordinates only, so images do not depend on threads or run order.

/// The offset inside pixel (px, py) of sample `s` of `n`, in [0, 1)².
/// One sample is the pixel centre.
pub fn offset(px: u32, py: u32, s: u32, n: u32) -> (f64, f64) {
    if n <= 1 {
        return (0.5, 0.5);
    }
    let seed = hash(((py as u64) << 32) | px as u64);
    let row = permute(s, n, seed as u32);
    let jx = unit(hash(seed ^ (2 * s as u64 + 1)));
    let jy = unit(hash(seed ^ (2 * s as u64 + 2) << 20));
    ((s as f64 + jx) / n as f64, (row as f64 + jy) / n as f64)
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
    fn samples_fill_every_row_and_column_stratum_once() {
        let n = 16;
        let mut rows = vec![0; n as usize];
        for s in 0..n {
            let (x, y) = offset(7, 9, s, n);
            assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
            assert_eq!((x * n as f64) as u32, s);
            rows[(y * n as f64) as usize] += 1;
        }
        assert!(rows.iter().all(|&c| c == 1), "{rows:?}");
    }

    #[test]
    fn one_sample_is_the_pixel_centre() {
        for (px, py) in [(0, 0), (7, 3), (4000, 12)] {
            assert_eq!(offset(px, py, 0, 1), (0.5, 0.5));
        }
    }

    #[test]
    fn samples_depend_on_the_pixel() {
        // Over a 16×16 block, the row stratum of sample 0 (of 4) and its
        // jitter vary from pixel to pixel: every stratum is used, and no two
        // pixels share an offset (a constant pattern would alias).
        let mut strata = [0u32; 4];
        let mut seen = Vec::new();
        for py in 0..16 {
            for px in 0..16 {
                let (x, y) = offset(px, py, 0, 4);
                strata[(y * 4.0) as usize] += 1;
                seen.push((x.to_bits(), y.to_bits()));
            }
        }
        assert!(strata.iter().all(|&c| c >= 32), "{strata:?}");
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 256);
    }
}
