//! What csgrt uses where a scene says nothing: material, lights, camera.

use super::{CameraSpec, Light, Material};
use crate::geometry::Aabb;
use glam::DVec3;

/// OpenSCAD's default face colour (the "Cornfield" scheme, #f9d72c) with a
/// soft Phong highlight; opaque and not reflective.
pub const MATERIAL: Material = Material {
    color: DVec3::new(249.0 / 255.0, 215.0 / 255.0, 44.0 / 255.0),
    ka: 0.2,
    kd: 0.8,
    ks: 0.3,
    ns: 30.0,
    kr: 0.0,
    kt: 0.0,
    ior: 1.5,
};

pub const BACKGROUND: DVec3 = DVec3::new(1.0, 1.0, 0.898);

/// An ambient term, a key light from the upper left of the default view and
/// a weaker fill from the right, so every face of a cube reads differently.
pub fn lights() -> Vec<Light> {
    vec![
        Light::Ambient { color: DVec3::ONE },
        Light::Directional {
            color: DVec3::splat(0.8),
            direction: -DVec3::new(-0.35, -0.6, 0.72).normalize(),
        },
        Light::Directional {
            color: DVec3::splat(0.35),
            direction: -DVec3::new(1.0, -0.25, 0.15).normalize(),
        },
    ]
}

/// The direction from the scene towards OpenSCAD's default eye: its view
/// rotation [55, 0, 25] turns +z to front (−y), right (+x) and above.
pub fn view_direction() -> DVec3 {
    let (ax, az) = (55f64.to_radians(), 25f64.to_radians());
    DVec3::new(ax.sin() * az.sin(), -ax.sin() * az.cos(), ax.cos())
}

pub const FOV: f64 = 30.0;

/// A camera that frames `bounds` (its bounded part) with a margin, z up,
/// from OpenSCAD's default direction. An empty scene gets a unit view.
pub fn framing_camera(bounds: &Aabb, width: u32, height: u32) -> CameraSpec {
    let b = if bounds.is_empty() || !bounds.is_bounded() {
        Aabb::new(DVec3::NEG_ONE, DVec3::ONE)
    } else {
        *bounds
    };
    let center = b.center();
    let radius = (0.5 * (b.max - b.min).length()).max(1e-9);
    let half_h = (FOV.to_radians() * 0.5).tan();
    let half_v = half_h * height as f64 / width as f64;
    let half = half_h.min(half_v).atan();
    let dist = radius * 1.1 / half.sin();
    CameraSpec {
        eye: center + view_direction() * dist,
        lookat: center,
        up: DVec3::Z,
        fov: FOV,
    }
}
