//! The closed set of primitive shapes, matched rather than boxed: this file
//! only lists them and dispatches to their modules (see [`Solid`]).

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{
    Aabb, Cone, Convex, Cuboid, Halfspace, Lathe, Mesh, OffsetPrism, Part, Prism, Ring, Rounded,
    Shadow, Sphere, Torus, Twisted,
};
use glam::{DAffine3, DVec3};

/// Not `Copy`: a leaf may carry shared data (a prism's region).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Cuboid(Cuboid),
    Cone(Cone),
    Torus(Torus),
    Halfspace(Halfspace),
    Prism(Prism),
    Lathe(Lathe),
    Twisted(Twisted),
    Mesh(Mesh),
    Shadow(Shadow),
    Convex(Convex),
    Rounded(Rounded),
    OffsetPrism(OffsetPrism),
    Ring(Ring),
}

/// `each!(shape, s => expr)`: `expr` with `s` bound to the primitive inside.
macro_rules! each {
    ($shape:expr, $s:ident => $e:expr) => {
        match $shape {
            Shape::Sphere($s) => $e,
            Shape::Cuboid($s) => $e,
            Shape::Cone($s) => $e,
            Shape::Torus($s) => $e,
            Shape::Halfspace($s) => $e,
            Shape::Prism($s) => $e,
            Shape::Lathe($s) => $e,
            Shape::Twisted($s) => $e,
            Shape::Mesh($s) => $e,
            Shape::Shadow($s) => $e,
            Shape::Convex($s) => $e,
            Shape::Rounded($s) => $e,
            Shape::OffsetPrism($s) => $e,
            Shape::Ring($s) => $e,
        }
    };
}

/// The name of solid `S`'s statement (a helper for [`each!`]).
fn name_of<S: Solid>(_: &S) -> &'static str {
    S::NAME
}

impl Shape {
    pub fn name(&self) -> &'static str {
        each!(self, s => name_of(s))
    }

    /// See [`Solid::spans`].
    #[inline]
    pub fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        each!(self, s => s.spans(q, emit))
    }

    /// See [`Solid::normal`].
    pub fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        each!(self, s => s.normal(p, part))
    }

    /// See [`Solid::flat_normal`].
    pub fn flat_normal(&self, part: Part) -> Option<DVec3> {
        each!(self, s => s.flat_normal(part))
    }

    /// See [`Solid::normal_on`].
    pub fn normal_on(&self, o: DVec3, d: DVec3, t: f64, part: Part) -> DVec3 {
        each!(self, s => s.normal_on(o, d, t, part))
    }

    /// See [`Solid::contains`].
    pub fn contains(&self, p: DVec3) -> bool {
        each!(self, s => s.contains(p))
    }

    /// See [`Solid::object_bounds`].
    pub fn object_bounds(&self) -> Aabb {
        each!(self, s => s.object_bounds())
    }

    /// See [`Solid::world_bounds`]: exact for spheres (ellipsoids), cone
    /// frusta (the hull of two elliptic discs) and tori (a circle swept by
    /// a ball), one-sided for half-spaces with an axis-aligned plane, the
    /// transformed object box for cubes.
    pub fn world_bounds(&self, m: &DAffine3) -> Aabb {
        each!(self, s => s.world_bounds(m))
    }

    /// See [`Solid::slab_bounds`].
    pub fn slab_bounds(&self, axis: usize, lo: f64, hi: f64) -> Aabb {
        each!(self, s => s.slab_bounds(axis, lo, hi))
    }

    /// See [`Solid::narrowing_axis`].
    pub fn narrowing_axis(&self) -> Option<usize> {
        each!(self, s => s.narrowing_axis())
    }

    /// See [`Solid::support`].
    pub fn support(&self, d: DVec3) -> Option<DVec3> {
        each!(self, s => s.support(d))
    }

    /// See [`Solid::params`].
    pub fn params(&self) -> Vec<(&'static str, Param)> {
        each!(self, s => s.params())
    }

    /// See [`Solid::pov`].
    pub fn pov(&self) -> String {
        each!(self, s => s.pov())
    }
}
