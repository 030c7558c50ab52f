//! Affine transforms with their inverse and normal matrix cached.

use super::Ray;
use glam::{DAffine3, DMat3, DVec3};

/// The largest magnitude of a transform's entries (sizes, positions and
/// their products), and of its inverse's. Beyond it, squared distances in
/// the ray tests would lose all precision long before they overflow.
pub const MAX_MAGNITUDE: f64 = 1e15;

/// Why a matrix cannot place a solid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degenerate {
    /// Singular or nearly so: the solid has no volume.
    Flat,
    /// Sizes or positions beyond [`MAX_MAGNITUDE`], or not finite.
    OutOfRange,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Object space → world.
    pub to_world: DAffine3,
    /// World → object space.
    pub to_object: DAffine3,
    /// The inverse transpose of the linear part: object normals → world.
    /// It keeps outward normals outward under mirrors (negative determinant).
    pub normal: DMat3,
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        to_world: DAffine3::IDENTITY,
        to_object: DAffine3::IDENTITY,
        normal: DMat3::IDENTITY,
    };

    /// The transform of a solid, or why it cannot be one: its entries
    /// exceed [`MAX_MAGNITUDE`] ([`Degenerate::OutOfRange`]), or it flattens
    /// the solid — singular, or so nearly that its inverse's entries exceed
    /// the same bound, a solid thinner than 1/[`MAX_MAGNITUDE`] of its size
    /// ([`Degenerate::Flat`]).
    pub fn new(to_world: DAffine3) -> Result<Transform, Degenerate> {
        let over = |v: &f64| v.is_nan() || v.abs() > MAX_MAGNITUDE;
        if to_world.to_cols_array().iter().any(over) {
            return Err(Degenerate::OutOfRange);
        }
        if to_world.matrix3.determinant() == 0.0 {
            return Err(Degenerate::Flat);
        }
        let to_object = to_world.inverse();
        if to_object.matrix3.to_cols_array().iter().any(over) {
            return Err(Degenerate::Flat);
        }
        Ok(Transform {
            to_world,
            to_object,
            normal: to_object.matrix3.transpose(),
        })
    }

    /// The ray in object space; `t` keeps its meaning.
    ///
    /// The origin is taken relative to the object's own origin in world
    /// space first, `M⁻¹·(o − c)`, not as `M⁻¹·o − M⁻¹·c`: for a small part
    /// far from the world origin the two terms of the latter are huge and
    /// cancel, while `o − c` is exact or nearly so for a ray near the part.
    pub fn ray_to_object(&self, ray: &Ray) -> (DVec3, DVec3) {
        (
            self.point_to_object(ray.origin),
            self.dir_to_object(ray.dir),
        )
    }

    /// A world point in object space, computed the same careful way.
    pub fn point_to_object(&self, p: DVec3) -> DVec3 {
        self.to_object.matrix3 * (p - self.to_world.translation)
    }

    /// A world direction in object space, as a ray's.
    pub fn dir_to_object(&self, d: DVec3) -> DVec3 {
        self.to_object.matrix3 * d
    }

    /// A unit world normal from an object-space normal.
    pub fn normal_to_world(&self, n: DVec3) -> DVec3 {
        (self.normal * n).normalize()
    }
}
