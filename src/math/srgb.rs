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
/// `decode((k + ½) / 255)`.
fn steps() -> &'static [f64; 255] {
    static STEPS: OnceLock<[f64; 255]> = OnceLock::new();
    STEPS.get_or_init(|| std::array::from_fn(|k| decode((k as f64 + 0.5) / 255.0)))
}

/// A linear channel value as an sRGB byte: round(255·encode(v)), halves
/// up, after clamping to [0, 1]; NaN gives 0. Found by eight comparisons
/// with the values where the byte steps (no power function per pixel).
#[inline]
pub fn byte(v: f64) -> u8 {
    let s = steps();
    let mut i = 0usize;
    for step in [128, 64, 32, 16, 8, 4, 2, 1] {
        if v >= s[i + step - 1] {
            i += step;
        }
    }
    i as u8
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
        for (k, &t) in steps().iter().enumerate() {
            assert_eq!(byte(t * (1.0 + 1e-12)), k as u8 + 1);
            assert_eq!(byte(t * (1.0 - 1e-12)), k as u8);
        }
        assert_eq!(byte(-1.0), 0);
        assert_eq!(byte(2.0), 255);
        assert_eq!(byte(f64::NAN), 0);
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
