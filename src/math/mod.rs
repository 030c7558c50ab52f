//! Numbers below geometry: the set operations ([`boolean`]), real roots of polynomials ([`poly`]), the sign
//! changes of trigonometric polynomials ([`trig`]) and the floating-point
//! error policy for secondary rays ([`robust`]), the sRGB transfer function
//! ([`srgb`]). No geometric type here.

pub mod boolean;
pub mod poly;
pub mod robust;
pub mod srgb;
pub mod trig;
