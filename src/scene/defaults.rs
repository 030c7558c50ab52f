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
    scheme_color: true,
};

/// An OpenSCAD colour scheme: the background and the face colour of its
/// preview (`color-schemes/render/*.json`, `colormap.cc`, 2021.01).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColorScheme {
    pub name: &'static str,
    pub background: DVec3,
    pub face: DVec3,
}

const fn hex(rgb: u32) -> DVec3 {
    DVec3::new(
        ((rgb >> 16) & 255) as f64 / 255.0,
        ((rgb >> 8) & 255) as f64 / 255.0,
        (rgb & 255) as f64 / 255.0,
    )
}

const fn scheme(name: &'static str, background: u32, face: u32) -> ColorScheme {
    ColorScheme {
        name,
        background: hex(background),
        face: hex(face),
    }
}

/// OpenSCAD 2021.01's colour schemes, in its menu's order; the first is
/// its default and csgrt's.
pub const COLOR_SCHEMES: [ColorScheme; 11] = [
    scheme("Cornfield", 0xffffe5, 0xf9d72c),
    scheme("Metallic", 0xaaaaff, 0xddddff),
    scheme("Sunset", 0xaa4444, 0xffaaaa),
    scheme("Starnight", 0x000000, 0xffffe0),
    scheme("BeforeDawn", 0x333333, 0xcccccc),
    scheme("Nature", 0xfafafa, 0x16a085),
    scheme("DeepOcean", 0x333333, 0xeeeeee),
    scheme("Solarized", 0xfdf6e3, 0xb58800),
    scheme("Tomorrow", 0xf8f8f8, 0x4271ae),
    scheme("Tomorrow Night", 0x1d1f21, 0x81a2be),
    scheme("Monotone", 0xffffe5, 0xf9d72c),
];

pub const BACKGROUND: DVec3 = DVec3::new(1.0, 1.0, 0.898);

/// The rig used where a scene gives no lights, placed about the camera
/// `cam` as OpenSCAD places its own: an ambient term; a key light from the
/// upper left in front, the only one that casts shadows; a shadowless
/// fill from the right and a shadowless top light, so that a face turned
/// from the key is still lit and a shadow darkens without hiding. With the
/// default material (ka 0.2, kd 0.8) a face square to the key gets all of
/// its colour, the faces of a box in the default view (top, front, right)
/// 0.96, 0.52 and 0.32 of it (linear; 0.98, 0.75, 0.60 encoded as sRGB),
/// and no face less than 0.2 (0.48); a shadow leaves a face about two
/// thirds of its lit brightness (sRGB).
pub fn lights(cam: &CameraSpec) -> Vec<Light> {
    let forward = (cam.lookat - cam.eye).normalize();
    let right = forward.cross(cam.up).normalize();
    let up = right.cross(forward);
    // A direction towards a light, given in the camera's right, up and
    // back axes.
    let from = |r: f64, u: f64, b: f64| (r * right + u * up - b * forward).normalize();
    let travel = |color: f64, towards: DVec3, shadows: bool| Light::Directional {
        color: DVec3::splat(color),
        direction: -towards,
        shadows,
    };
    vec![
        Light::Ambient { color: DVec3::ONE },
        travel(0.85, from(-0.5, 0.5, 0.7), true),
        travel(0.15, from(0.9, -0.1, 0.45), false),
        travel(0.25, from(0.0, 1.0, 0.2), false),
    ]
}

/// The direction from the scene towards OpenSCAD's default eye: its view
/// rotation [55, 0, 25] turns +z to front (−y), right (+x) and above.
pub fn view_direction() -> DVec3 {
    let (ax, az) = (55f64.to_radians(), 25f64.to_radians());
    DVec3::new(ax.sin() * az.sin(), -ax.sin() * az.cos(), ax.cos())
}

pub const FOV: f64 = 30.0;

/// How much of the frame the framed box may fill, per side.
const FILL: f64 = 0.9;

/// A camera that frames `bounds` from OpenSCAD's default direction, z up:
/// the eye is pulled back just far enough that all eight corners of the
/// box fall inside the central 90 % of the frame. An empty or unbounded
/// box gets the view of the cube [-1, 1]³.
pub fn framing_camera(bounds: &Aabb, width: u32, height: u32) -> CameraSpec {
    let b = if bounds.is_empty() || !bounds.is_bounded() {
        Aabb::new(DVec3::NEG_ONE, DVec3::ONE)
    } else {
        *bounds
    };
    let center = b.center();
    let back = view_direction();
    let forward = -back;
    let right = forward.cross(DVec3::Z).normalize();
    let up = right.cross(forward);
    let tan_h = (FOV.to_radians() * 0.5).tan() * FILL;
    let tan_v = tan_h * height as f64 / width as f64;
    let radius = 0.5 * (b.max - b.min).length();
    // The eye stays outside the box's bounding sphere.
    let mut dist: f64 = radius * 1.01;
    for i in 0..8 {
        let corner = DVec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        let o = corner - center;
        let depth = o.dot(forward);
        dist = dist
            .max(o.dot(right).abs() / tan_h - depth)
            .max(o.dot(up).abs() / tan_v - depth);
    }
    let dist = dist.max(1e-9);
    CameraSpec {
        eye: center + back * dist,
        lookat: center,
        up: DVec3::Z,
        fov: FOV,
        projection: Default::default(),
    }
}
