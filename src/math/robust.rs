//! The floating-point error policy, in one place.
//!
//! csgrt never uses a fixed "epsilon" to dodge self-intersection. Instead a
//! secondary ray starts from the hit point moved off the surface, along the
//! normal, by a bound on the error of that point (pbrt-v4's
//! `OffsetRayOrigin`, Ray Tracing Gems ch. 6):
//!
//! * a hit point `p = o + t·d` computed in f64 is off the true surface by at
//!   most a few ulps of its largest coordinate, plus whatever error the
//!   object-space solve had, which for our solvers is a small multiple of the
//!   ulp of the point's coordinates in object space, carried to the world by
//!   the transform;
//! * [`point_error`] bounds that as `ERROR_ULPS · ε · (|p|∞ + |o|∞ + |t·d|∞)`;
//! * [`offset_origin`] moves the point by that bound along the normal, to the
//!   side the new ray travels into.
//!
//! Because the bound scales with the coordinates, parts a million units from
//! the origin and micron-thin shells near it are both handled.

use glam::DVec3;

/// γₙ = nε / (1 − nε), the usual bound on n chained rounding errors.
pub const fn gamma(n: u32) -> f64 {
    let ne = n as f64 * f64::EPSILON * 0.5;
    ne / (1.0 - ne)
}

pub const GAMMA3: f64 = gamma(3);

/// How many ulps of the coordinates a hit point may be off: the transforms
/// into and out of object space, the root of the solve and the final
/// `o + t·d` each add a few. Measured with `tests/it/self_intersection.rs`
/// (2000 random convex parts, sizes 1e-3 to 1e3, offsets to 1e6): it fails
/// at 1 and passes at 4; 32 keeps an 8× margin while moving a secondary
/// ray only 1.6e-8 off a surface a million units out.
pub const ERROR_ULPS: f64 = 32.0;

/// How many ulps of the ray's scale two boundaries of different operands
/// may differ by and still be the same surface (see [`coincidence`]).
pub const COINCIDENT_ULPS: f64 = 256.0;

/// The distance along a ray below which two computed boundaries are one.
///
/// Two primitives that share a face (a cube minus a cube flush with its top)
/// reach it through different transforms, so their computed `t` differ by a
/// few ulps of the ray's coordinates. Left apart, a difference would keep a
/// sliver that thin and show the shared face as speckles. The bound scales
/// with |t| and with the ray origin's coordinates (`origin_scale`, its
/// largest absolute component; directions are unit), the two sources of
/// the rounding in `t`. Features thinner than this are below what f64 can
/// place at those coordinates anyway.
pub fn coincidence(t: f64, origin_scale: f64) -> f64 {
    if !t.is_finite() {
        // The open end of an unbounded span is exactly where it is.
        return 0.0;
    }
    COINCIDENT_ULPS * f64::EPSILON * (t.abs() + origin_scale)
}

/// A bound on the distance between a computed hit point and the surface.
pub fn point_error(p: DVec3, origin: DVec3, t_dir: DVec3) -> f64 {
    let scale = p.abs().max_element() + origin.abs().max_element() + t_dir.abs().max_element();
    ERROR_ULPS * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
}

/// The origin for a ray leaving `p` along `dir`, moved off the surface with
/// normal `n` by `err` to the side `dir` points into.
pub fn offset_origin(p: DVec3, n: DVec3, err: f64, dir: DVec3) -> DVec3 {
    let offset = n * err;
    if dir.dot(n) < 0.0 {
        p - offset
    } else {
        p + offset
    }
}
