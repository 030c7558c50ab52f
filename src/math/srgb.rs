//! The sRGB transfer function (IEC 61966-2-1): colours as people write
//! them (OpenSCAD's `color`, a colour picker's numbers, an 8-bit file) are
//! sRGB-encoded; light adds up in linear values. A scene's colours are
//! decoded once when it is built, and an 8-bit pixel is encoded from the
//! linear radiance the shading gives.

use glam::DVec3;
use std::sync::OnceLock;

/// An sRGB-encoded channel value as a linear one (values outside [0, 1]
/// follow the same curve, mirrored below zero).
pub fn decode(c: f64) -> f64 {
    let a = c.abs();
    let l = if a <= 0.04045 {
        a / 12.92
    } else {
        ((a + 0.055) / 1.055).powf(2.4)
    };
    l.copysign(c)
}

/// A linear channel value in [0, 1] encoded as sRGB.
pub fn encode(l: f64) -> f64 {
    if l <= 0.0031308 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// [`decode`] of each channel.
pub fn decode3(c: DVec3) -> DVec3 {
    DVec3::new(decode(c.x), decode(c.y), decode(c.z))
}

/// The linear value at which the byte of [`byte`] steps from k to k + 1:
/// `decode((k + ½) / 255)`; past 255, infinity.
fn steps() -> &'static [f64; 256] {
    static STEPS: OnceLock<[f64; 256]> = OnceLock::new();
    STEPS.get_or_init(|| {
        std::array::from_fn(|k| match k {
            255 => f64::INFINITY,
            _ => decode((k as f64 + 0.5) / 255.0),
        })
    })
}

/// Linear values are bucketed by their exponent and top [`MANTISSA`] bits
/// (the bits of a non-negative `f64` are in the order of the values), from
/// 2^−[`LOWEST`] (below the first step, byte 0) up to 1 (byte 255).
const MANTISSA: u32 = 7;
const LOWEST: i32 = 14;
const SHIFT: u32 = 52 - MANTISSA;
const BUCKETS: usize = (LOWEST as usize) << MANTISSA;

fn first_bucket() -> u64 {
    (2f64).powi(-LOWEST).to_bits() >> SHIFT
}

/// Each bucket's byte at its lowest value: a bucket spans 1/128 of its
/// values, at most 0.85 of a byte once encoded, so a value's byte is its
/// bucket's or the next (a unit test checks every step).
fn buckets() -> &'static [u8; BUCKETS] {
    static BASE: OnceLock<[u8; BUCKETS]> = OnceLock::new();
    BASE.get_or_init(|| {
        std::array::from_fn(|k| {
            let lo = f64::from_bits((first_bucket() + k as u64) << SHIFT);
            searched(lo)
        })
    })
}

/// [`byte`] by binary search over the steps (eight comparisons).
fn searched(v: f64) -> u8 {
    let s = steps();
    let mut i = 0usize;
    for step in [128, 64, 32, 16, 8, 4, 2, 1] {
        if v >= s[i + step - 1] {
            i += step;
        }
    }
    i as u8
}

/// A linear channel value as an sRGB byte: round(255·encode(v)), halves
/// up, after clamping to [0, 1]; NaN gives 0. Found from the value's
/// bucket and one comparison with the step above it: no power function
/// and no search per pixel.
#[inline]
pub fn byte(v: f64) -> u8 {
    if v >= 1.0 {
        return 255;
    }
    let k = (v.to_bits() >> SHIFT).wrapping_sub(first_bucket());
    // Negative values, NaN and values below 2^−14 (k wraps, or is past
    // the table through the sign bit or NaN's exponent) are byte 0.
    match buckets().get(k as usize) {
        Some(&b) => b + (v >= steps()[b as usize]) as u8,
        None => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_is_the_rounded_encoding() {
        // The closed form, computed directly, on a fine grid and at both
        // sides of every step.
        let direct = |v: f64| (255.0 * encode(v.clamp(0.0, 1.0)) + 0.5).floor() as u8;
        for i in 0..=100_000 {
            let v = i as f64 / 100_000.0;
            assert_eq!(byte(v), direct(v), "at {v}");
        }
        for (k, &t) in steps()[..255].iter().enumerate() {
            assert_eq!(byte(t * (1.0 + 1e-12)), k as u8 + 1);
            assert_eq!(byte(t * (1.0 - 1e-12)), k as u8);
            // At the step itself and the floats around it, as the search.
            let mut x = f64::from_bits(t.to_bits() - 4);
            for _ in 0..9 {
                assert_eq!(byte(x), searched(x), "{x:e}");
                x = f64::from_bits(x.to_bits() + 1);
            }
        }
        // Every bucket's ends, as the search.
        for k in 0..BUCKETS as u64 {
            let lo = (first_bucket() + k) << SHIFT;
            for bits in [lo, lo + (1 << SHIFT) - 1] {
                let x = f64::from_bits(bits);
                assert_eq!(byte(x), searched(x), "{x:e}");
            }
        }
        assert_eq!(byte(-1.0), 0);
        assert_eq!(byte(2.0), 255);
        assert_eq!(byte(f64::NAN), 0);
        assert_eq!(byte(-0.0), 0);
        assert_eq!(byte(1e-300), 0);
        assert_eq!(byte(f64::NEG_INFINITY), 0);
        assert_eq!(byte(f64::INFINITY), 255);
    }

    #[test]
    fn decoding_inverts_encoding_and_keeps_every_byte() {
        for k in 0..=255u32 {
            let c = k as f64 / 255.0;
            let l = decode(c);
            assert!((encode(l) - c).abs() < 1e-12);
            assert_eq!(byte(l), k as u8);
        }
        // The standard's reference points.
        assert!((decode(0.5) - 0.214_041_140_482_232_5).abs() < 1e-12);
        assert_eq!(decode(0.04045), 0.04045 / 12.92);
    }
}
