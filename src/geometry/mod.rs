//! Geometry: rays, bounding boxes, affine transforms and the primitives.
//!
//! Every primitive is a generic solid in its own object space (the unit
//! sphere, the cube [-1, 1]³, …). A [`Transform`] maps it into the world; rays
//! are mapped into object space with the inverse, *without* renormalising the
//! direction, so the ray parameter `t` is the same in both spaces.

pub mod aabb;
pub mod ball_sum;
pub mod bvh;
pub mod coaxial;
pub mod coherence;
pub mod cone;
pub mod convex;
pub mod cuboid;
pub mod disc_hull;
pub mod disc_sum;
pub mod halfspace;
pub mod lathe;
pub mod mesh;
pub mod mesh_bvh;
pub mod mesh_cells;
pub mod offset_prism;
pub mod polytope;
pub mod prism;
pub mod quickhull;
pub mod ring;
pub mod rounded;
pub mod shadow;
pub mod shape;
pub mod solid;
pub mod sphere;
pub mod torus;
pub mod transform;
pub mod trapezoids;
pub mod triangulate;
pub mod twist;

pub use aabb::Aabb;
pub use cone::Cone;
pub use convex::Convex;
pub use cuboid::Cuboid;
pub use halfspace::Halfspace;
pub use lathe::Lathe;
pub use mesh::Mesh;
pub use offset_prism::OffsetPrism;
pub use prism::Prism;
pub use ring::Ring;
pub use rounded::Rounded;
pub use shadow::Shadow;
pub use shape::Shape;
pub use solid::{Need, Param, Probe, Solid};
pub use sphere::Sphere;
pub use torus::Torus;
pub use transform::Transform;
pub use twist::{TwistSection, Twisted};

use glam::DVec3;

/// A ray `origin + t·dir`. World rays have a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
    /// Componentwise `1 / dir` (±∞ for zero components), for slab tests.
    pub inv_dir: DVec3,
}

impl Ray {
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray {
            origin,
            dir,
            inv_dir: DVec3::ONE / dir,
        }
    }

    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// Which part of a primitive's surface a crossing lies on (a cube face, a
/// cylinder cap, a mesh's triangle, a polygon's edge: 31 bits);
/// [`NO_PART`] marks the open end of an unbounded span.
pub type Part = u32;
pub const NO_PART: Part = (1 << 31) - 1;
