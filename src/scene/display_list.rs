//! The seed's display list ([`RayStatement`]s) → [`Scene`].
//!
//! The format is flat, so it is read straight into a scene (through the one
//! [`SceneBuilder`]): the camera and
//! background statements set the view, `light` adds a light, `surface`
//! sets the material of the spheres after it, `sphere` adds one. All the
//! spheres form a union. Colours and coefficients are in [0, 1] (the
//! lecture's applet divided kr and kt by 255 because its colours were
//! bytes; csgrt's are not).

use super::builder::SceneBuilder;
use super::{defaults, CameraSpec, Light, Material, Scene};
use crate::error::{Result, TextRange};
use crate::geometry::transform::MAX_MAGNITUDE;
use crate::geometry::{Shape, Transform};
use crate::source::Source;
use crate::syntax::ray::{RayLight, RayStatement};
use glam::{DAffine3, DVec3};

/// A display list's statements made a scene.
pub fn resolve_ray(src: &Source, statements: &[(RayStatement, TextRange)]) -> Result<Scene> {
    let mut cam = CameraSpec {
        eye: DVec3::new(0.0, 0.0, 10.0),
        lookat: DVec3::ZERO,
        up: DVec3::Y,
        fov: 30.0,
        projection: Default::default(),
    };
    let mut b = SceneBuilder::new();
    let mut current: Option<u32> = None;
    let mut spheres = Vec::new();
    let mut camera_span = None;
    for (st, span) in statements {
        let span = *span;
        // The first camera statement is where a degenerate camera is reported.
        if let RayStatement::Eye(_)
        | RayStatement::Lookat(_)
        | RayStatement::Up(_)
        | RayStatement::Fov(_) = st
        {
            camera_span.get_or_insert(span);
        }
        match st {
            RayStatement::Eye(v) => cam.eye = *v,
            RayStatement::Lookat(v) => cam.lookat = *v,
            RayStatement::Up(v) => cam.up = *v,
            RayStatement::Fov(f) => {
                if !(*f > 0.0 && *f < 180.0) {
                    return Err(src.error(
                        span,
                        "the field of view is out of range",
                        "expected degrees strictly between 0 and 180",
                    ));
                }
                cam.fov = *f;
            }
            RayStatement::Background(c) => b.background = Some(*c),
            RayStatement::Light { color, kind } => {
                let color = *color;
                let light = match *kind {
                    RayLight::Ambient => Light::Ambient { color },
                    RayLight::Directional(d) => {
                        if d.length_squared() == 0.0 {
                            return Err(src.error(
                                span,
                                "a light's direction must not be zero",
                                "expected a non-zero direction",
                            ));
                        }
                        Light::Directional {
                            color,
                            direction: d.normalize(),
                            shadows: true,
                        }
                    }
                    RayLight::Point(position) => Light::Point { color, position },
                };
                b.lights.push(light);
            }
            RayStatement::Surface(n) => {
                if n[3..].iter().any(|x| *x < 0.0) || n[9] == 0.0 {
                    return Err(src.error(
                        span,
                        "a surface's coefficients must not be negative, nor its index zero",
                        "expected `surface r g b ka kd ks ns kr kt nt`",
                    ));
                }
                let m = Material {
                    color: DVec3::new(n[0], n[1], n[2]),
                    ka: n[3],
                    kd: n[4],
                    ks: n[5],
                    ns: n[6],
                    kr: n[7],
                    kt: n[8],
                    ior: n[9],
                    scheme_color: false,
                };
                current = Some(b.material_id(m));
            }
            RayStatement::Sphere(n) => {
                if n[3] <= 0.0 {
                    return Err(src.error(
                        span,
                        "a sphere's radius must be positive",
                        "expected `sphere x y z r` with r > 0",
                    ));
                }
                let material = *current.get_or_insert_with(|| b.material_id(defaults::MATERIAL));
                let r = if crate::mutant::active("sphere_small") {
                    0.97 * n[3]
                } else {
                    n[3]
                };
                let centre = DVec3::new(n[0], n[1], n[2]);
                let m = DAffine3::from_translation(centre) * DAffine3::from_scale(DVec3::splat(r));
                let Ok(xf) = Transform::new(m) else {
                    return Err(src.error(
                        span,
                        "this sphere is out of range",
                        format!(
                            "expected a centre within ±{MAX_MAGNITUDE:e} and a radius from {:e} to {MAX_MAGNITUDE:e}",
                            1.0 / MAX_MAGNITUDE
                        ),
                    ));
                };
                spheres.push(b.leaf(Shape::Sphere(crate::geometry::Sphere), xf, material));
            }
        }
    }
    let look = cam.lookat - cam.eye;
    if look.cross(cam.up).length_squared() == 0.0 {
        return Err(src.error(
            camera_span.unwrap_or_default(),
            "the camera is degenerate",
            "expected `eye` apart from `lookat`, and `up` not along the view",
        ));
    }
    b.camera = Some(cam);
    let root = b.union(spheres);
    // The lecture's display lists have a black background by default.
    Ok(b.finish(src, root, TextRange::default(), DVec3::ZERO))
}
