//! Numbers below geometry: the set operations ([`boolean`]), real roots of polynomials ([`poly`]), the sign
//! changes of trigonometric polynomials ([`trig`]) and the floating-point
//! error policy for secondary rays ([`robust`]), the sRGB transfer function
//! ([`srgb`]). No geometric type here.

pub mod boolean;
pub mod poly;
pub mod robust;
pub mod srgb;
pub mod trig;

/// For unit tests: a deterministic stream of numbers in [0, 1) from
/// `seed` (a 64-bit linear congruential generator's top 53 bits).
#[cfg(test)]
pub fn test_stream(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}
