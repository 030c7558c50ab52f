//! The seed's pinhole camera (slide 6), exactly as LANGUAGE.md gives it.
//!
//! `look = lookat − eye`, `Du = normalize(look × up)`,
//! `Dv = normalize(look × Du)`, `fl = width / (2·tan(fov/2))`,
//! `Vp = normalize(look)·fl − ½(width·Du + height·Dv)`; the ray through
//! image point (x, y) — column i, row j has its centre at (i + ½, j + ½),
//! row 0 at the top — goes from the eye along `x·Du + y·Dv + Vp`.
//!
//! Orthographic (OpenSCAD's `--projection=ortho`): every ray goes along
//! `look`; the image shows the rectangle of the plane through `lookat`
//! that the perspective view shows there, `2·|look|·tan(fov/2)` wide. The
//! rays start `100·|look|` behind the eye, where OpenSCAD's `glOrtho` puts
//! its near plane, so what lies behind the eye is seen as OpenSCAD shows it.

use crate::geometry::Ray;
use crate::scene::{CameraSpec, Projection};
use glam::DVec3;

/// How many `|lookat − eye|` behind the eye orthographic rays start
/// (OpenSCAD's `glOrtho` near plane).
pub const ORTHO_BACK: f64 = 100.0;

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: DVec3,
    pub du: DVec3,
    pub dv: DVec3,
    pub vp: DVec3,
    /// Orthographic: the direction of every ray (`eye`, `du`, `dv` and
    /// `vp` then place its origin); `None` for the pinhole.
    pub parallel: Option<DVec3>,
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
        let forward = look.normalize();
        if spec.projection == Projection::Orthographic {
            // World units per pixel: the perspective view's at `lookat`.
            let s = look.length() / fl;
            return Camera {
                eye: spec.eye - ORTHO_BACK * look,
                du: s * du,
                dv: s * dv,
                vp: -0.5 * s * (w * du + h * dv),
                parallel: Some(forward),
            };
        }
        let vp = forward * fl - 0.5 * (w * du + h * dv);
        Camera {
            eye: spec.eye,
            du,
            dv,
            vp,
            parallel: None,
        }
    }

    /// The image point (x, y) whose ray passes through world point `p`,
    /// with how far ahead of the ray's origin `p` lies along the view
    /// (positive: ahead). The inverse of [`Camera::ray`]: `du`, `dv` and
    /// the view's direction are perpendicular, so each coordinate is one
    /// projection.
    pub fn project(&self, p: DVec3) -> (f64, f64, f64) {
        match self.parallel {
            None => {
                // A ray's direction x·du + y·dv + vp is parallel to p − eye
                // where their parts along du, dv and the view are in
                // proportion.
                let ahead = self.du.cross(self.dv);
                let rel = p - self.eye;
                let c = rel.dot(ahead) / self.vp.dot(ahead);
                let (x, y) = (rel.dot(self.du) / c, rel.dot(self.dv) / c);
                (x - self.vp.dot(self.du), y - self.vp.dot(self.dv), c)
            }
            Some(d) => {
                let rel = p - self.eye - self.vp;
                let (x, y) = (
                    rel.dot(self.du) / self.du.length_squared(),
                    rel.dot(self.dv) / self.dv.length_squared(),
                );
                (x, y, rel.dot(d))
            }
        }
    }

    /// The ray through image point (x, y), in pixels from the top left.
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let across = x * self.du + y * self.dv + self.vp;
        match self.parallel {
            None => Ray::new(self.eye, across.normalize()),
            Some(d) => Ray::new(self.eye + across, d),
        }
    }
}
