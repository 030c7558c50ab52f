//! The seed's pinhole camera (slide 6), exactly as LANGUAGE.md gives it.
//!
//! `look = lookat − eye`, `Du = normalize(look × up)`,
//! `Dv = normalize(look × Du)`, `fl = width / (2·tan(fov/2))`,
//! `Vp = normalize(look)·fl − ½(width·Du + height·Dv)`; the ray through
//! image point (x, y) — column i, row j has its centre at (i + ½, j + ½),
//! row 0 at the top — goes from the eye along `x·Du + y·Dv + Vp`.

use crate::geometry::Ray;
use crate::scene::CameraSpec;
use glam::DVec3;

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: DVec3,
    pub du: DVec3,
    pub dv: DVec3,
    pub vp: DVec3,
}

impl Camera {
    pub fn new(spec: &CameraSpec, width: u32, height: u32) -> Camera {
        let (w, h) = (width as f64, height as f64);
        let look = spec.lookat - spec.eye;
        let du = look.cross(spec.up).normalize();
        let dv = look.cross(du).normalize();
        let side = if crate::mutant::active("fov_vertical") {
            h
        } else {
            w
        };
        let fl = side / (2.0 * (0.5 * spec.fov).to_radians().tan());
        let vp = look.normalize() * fl - 0.5 * (w * du + h * dv);
        Camera {
            eye: spec.eye,
            du,
            dv,
            vp,
        }
    }

    /// The ray through image point (x, y), in pixels from the top left.
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        Ray::new(self.eye, (x * self.du + y * self.dv + self.vp).normalize())
    }
}
