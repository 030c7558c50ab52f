//! Affine transforms with their inverse and normal matrix cached.

use super::Ray;
use glam::{DAffine3, DMat3, DVec3};

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

    /// `None` when the matrix is singular (a flattened solid) or not finite.
    pub fn new(to_world: DAffine3) -> Option<Transform> {
        let det = to_world.matrix3.determinant();
        if !det.is_finite() || det == 0.0 || !to_world.translation.is_finite() {
            return None;
        }
        let to_object = to_world.inverse();
        if !to_object.matrix3.is_finite() || !to_object.translation.is_finite() {
            return None;
        }
        Some(Transform {
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
        let m = self.to_object.matrix3;
        (m * (ray.origin - self.to_world.translation), m * ray.dir)
    }

    /// A world point in object space, computed the same careful way.
    pub fn point_to_object(&self, p: DVec3) -> DVec3 {
        self.to_object.matrix3 * (p - self.to_world.translation)
    }

    /// A unit world normal from an object-space normal.
    pub fn normal_to_world(&self, n: DVec3) -> DVec3 {
        (self.normal * n).normalize()
    }
}
