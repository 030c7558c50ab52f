//! What every primitive answers about itself, in its own object space.
//!
//! A primitive is one module of `geometry/` with a struct that implements
//! [`Solid`]; [`super::Shape`] lists them and only dispatches. Everything
//! about a primitive — its spans, normal, inside test, bounds, support
//! function, its fields in `--dump-scene` and its POV-Ray object — lives in
//! its module.

use super::{Aabb, Part};
use crate::stats::Stats;
use glam::{DAffine3, DVec3};

/// Where the line enters and leaves a solid: `(t_in, part_in, t_out, part_out)`.
pub type RawSpan = (f64, Part, f64, Part);

/// The spans of a line cut at `roots` (sorted, in a unit-speed parameter s
/// from 0 to `span` over its clipped part, which starts at t = `lo`, ends at
/// `hi` and runs `len` per unit of t), each piece between two cuts inside
/// where `inside` says so at its middle; the ends of the clipped part are
/// outside. Entries and exits are part 0.
pub fn spans_between_roots(
    roots: &[f64],
    (span, lo, hi, len): (f64, f64, f64, f64),
    inside: impl Fn(f64) -> bool,
    emit: &mut impl FnMut(RawSpan),
) {
    let mut prev = 0.0;
    let mut from = None;
    for &r in roots.iter().chain(std::iter::once(&span)) {
        match (inside(0.5 * (prev + r)), from) {
            (true, None) => from = Some(prev),
            (false, Some(s0)) => {
                emit((lo + s0 / len, 0, lo + prev / len, 0));
                from = None;
            }
            _ => {}
        }
        prev = r;
    }
    if let Some(s0) = from {
        emit((lo + s0 / len, 0, hi, 0));
    }
}

/// What a primitive is asked for its spans: the line `o + t·d` in its
/// object space (d not normalised, so t is the world ray's), the range of t
/// the caller needs — spans may reach past it, a primitive with many parts
/// (a mesh) may stop there — and the counters of the work done.
pub struct Probe<'a> {
    pub o: DVec3,
    pub d: DVec3,
    pub tmin: f64,
    pub tmax: f64,
    pub st: &'a mut Stats,
    /// What the caller will read of the spans.
    pub need: Need,
}

/// What a span query's caller reads of the answer. The CSG asks for less
/// than every span only where it can show that less decides the answer:
/// a scene whose whole tree is one primitive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    /// Every span meeting (tmin, tmax), exactly.
    Spans,
    /// Only the first boundary after tmin, with its side (a first hit):
    /// the spans may be cut there and left open beyond.
    FirstBoundary,
    /// Only whether a boundary lies in (tmin, tmax) (a shadow ray): a leaf
    /// may answer with any of them (a mesh, the first its hierarchy meets),
    /// and its side does not matter.
    AnyBoundary,
}

/// A value a primitive reports about itself (for `--dump-scene`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Param {
    Bool(bool),
    Num(f64),
}

pub trait Solid {
    /// The OpenSCAD statement it comes from.
    const NAME: &'static str;

    /// Calls `emit` for each span of the probe's line inside the solid, in
    /// increasing `t`, at least those that meet (tmin, tmax). Spans are
    /// never empty (`t_in < t_out`); unbounded ends are ±∞ with part
    /// [`super::NO_PART`].
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan));

    /// The outward (not unit) normal at object-space point `p` on `part`.
    fn normal(&self, p: DVec3, part: Part) -> DVec3;

    /// The outward normal [`Solid::normal_on`] gives on `part` wherever it
    /// is met, if `part` is flat (a box's face, a half-space's plane):
    /// what a hit there may look up instead of computing. `None` by
    /// default.
    fn flat_normal(&self, _part: Part) -> Option<DVec3> {
        None
    }

    /// The outward normal where the line o + t·d crosses `part` at t: the
    /// normal at the point, for every solid that knows it from the point
    /// alone (a convex set known by its support does not).
    fn normal_on(&self, o: DVec3, d: DVec3, t: f64, part: Part) -> DVec3 {
        self.normal(o + t * d, part)
    }

    /// Whether object-space point `p` is inside (boundary counts as inside).
    fn contains(&self, p: DVec3) -> bool;

    /// A box around the solid in object space.
    fn object_bounds(&self) -> Aabb;

    /// A world box of the solid under `m`; by default the box of the
    /// transformed corners of the object box.
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        corner_box(&self.object_bounds(), m)
    }

    /// A box (object space) around the part of the solid whose `axis`
    /// coordinate lies in [lo, hi]; by default the object box cut there.
    fn slab_bounds(&self, axis: usize, lo: f64, hi: f64) -> Aabb {
        slab_of(self.object_bounds(), axis, lo, hi)
    }

    /// The axis along which the solid's slabs have boxes much smaller
    /// than its own (a twisted or tapered prism's z): worth slicing it
    /// along even where its box is not long.
    fn narrowing_axis(&self) -> Option<usize> {
        None
    }

    /// The point of the solid's convex hull farthest along `d` (object
    /// space, `d` not zero), or `None` for an unbounded solid.
    fn support(&self, d: DVec3) -> Option<DVec3>;

    /// The fields `--dump-scene` writes besides the matrix.
    fn params(&self) -> Vec<(&'static str, Param)>;

    /// The POV-Ray 3.7 object in the same object space, up to (not
    /// including) its transform and texture: `sphere { <0, 0, 0>, 1`.
    fn pov(&self) -> String;
}

/// Box `b` cut to the slab lo ≤ `axis` ≤ hi.
pub fn slab_of(mut b: Aabb, axis: usize, lo: f64, hi: f64) -> Aabb {
    b.min[axis] = b.min[axis].max(lo);
    b.max[axis] = b.max[axis].min(hi);
    b
}

/// The box of the eight transformed corners of `b`.
pub fn corner_box(b: &Aabb, m: &DAffine3) -> Aabb {
    let mut out = Aabb::EMPTY;
    for i in 0..8 {
        let p = DVec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        out = out.include(m.transform_point3(p));
    }
    out
}
