//! OpenSCAD's command-line camera (`--camera`, `--viewall`, `--autocenter`,
//! `--projection`), as OpenSCAD 2021.01 sets it up for a PNG export
//! (`openscad.cc` `get_camera`, `Camera.cc`, `GLView::setupCamera`).
//!
//! OpenSCAD keeps a "gimbal": a translation `object_trans` (= −`$vpt`),
//! angles `object_rot` (= 90° − `$vpr`.x, −`$vpr`.y, −`$vpr`.z, each
//! wrapped into [0°, 360°)), a viewer distance and a vertical field of
//! view of 22.5°. A world point p is seen at `Rx·Ry·Rz·(p + object_trans)`
//! by an eye at (0, −distance, 0) looking at the origin with z up; so the
//! eye, centre and up in the world are those turned back by `(Rx·Ry·Rz)ᵀ`
//! and moved by −`object_trans`. `viewall` moves the eye back to
//! `radius / sin(fov/2)`, radius being the distance from the centre to the
//! box's centre plus half its diagonal (after `autocenter` has put the
//! centre on the box's centre); without `--camera` both are on, from the
//! default view `$vpr` = [55, 0, 25].

use super::{CameraSpec, Projection};
use crate::geometry::Aabb;
use glam::{DMat3, DVec3};

/// OpenSCAD's default vertical field of view, degrees.
pub const FOV_Y: f64 = 22.5;
/// OpenSCAD's viewer distance for an empty scene, and of its default
/// view.
pub const DEFAULT_DISTANCE: f64 = 140.0;
/// OpenSCAD's default `$vpr`, degrees.
pub const DEFAULT_ROTATION: DVec3 = DVec3::new(55.0, 0.0, 25.0);

/// The two forms of `--camera`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Viewpoint {
    /// `tx,ty,tz,rx,ry,rz,dist`: `$vpt`, `$vpr` and `$vpd`.
    Gimbal {
        translate: DVec3,
        rotate: DVec3,
        distance: f64,
    },
    /// `ex,ey,ez,cx,cy,cz`: the eye and the point it looks at.
    Vector { eye: DVec3, center: DVec3 },
}

impl Viewpoint {
    /// The camera a program's `$vp*` give: OpenSCAD's default view
    /// (`$vpt` = 0, `$vpr` = [55, 0, 25], `$vpd` = 140) with what the
    /// program sets in place of its parts.
    pub fn of_scad(v: crate::import::scad::ScadView) -> Viewpoint {
        Viewpoint::Gimbal {
            translate: v.translate.map_or(DVec3::ZERO, DVec3::from),
            rotate: v.rotate.map_or(DEFAULT_ROTATION, DVec3::from),
            distance: v.distance.unwrap_or(DEFAULT_DISTANCE),
        }
    }

    /// OpenSCAD's parse of `--camera`: 7 numbers are a gimbal, 6 a vector.
    pub fn parse(s: &str) -> Result<Viewpoint, String> {
        let bad = || {
            format!(
                "`{s}` is not a camera: expected 7 numbers tx,ty,tz,rx,ry,rz,dist \
                 (translate, rotate in degrees, distance) or 6 numbers ex,ey,ez,cx,cy,cz \
                 (eye and centre), separated by commas"
            )
        };
        let v: Vec<f64> = s
            .split(',')
            .map(|p| p.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        if v.iter().any(|x| !x.is_finite()) {
            return Err(bad());
        }
        let v3 = |i: usize| DVec3::new(v[i], v[i + 1], v[i + 2]);
        match v.len() {
            7 => {
                if v[6] <= 0.0 {
                    return Err(format!("`{s}`: the distance (7th number) must be above 0"));
                }
                Ok(Viewpoint::Gimbal {
                    translate: v3(0),
                    rotate: v3(3),
                    distance: v[6],
                })
            }
            6 => {
                if v3(0) == v3(3) {
                    return Err(format!("`{s}`: the eye and the centre are the same point; expected two different points"));
                }
                Ok(Viewpoint::Vector {
                    eye: v3(0),
                    center: v3(3),
                })
            }
            _ => Err(bad()),
        }
    }
}

/// What the command line says about the view.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViewOptions {
    pub camera: Option<Viewpoint>,
    pub viewall: bool,
    pub autocenter: bool,
    pub projection: Option<Projection>,
}

impl ViewOptions {
    /// Whether OpenSCAD's camera replaces the file's camera or csgrt's
    /// framing: any of `--camera`, `--viewall`, `--autocenter`.
    pub fn is_openscad(&self) -> bool {
        self.camera.is_some() || self.viewall || self.autocenter
    }
}

/// OpenSCAD's gimbal state.
#[derive(Clone, Copy, Debug)]
struct Gimbal {
    object_trans: DVec3,
    /// Degrees, as `glRotated` takes them.
    object_rot: DVec3,
    distance: f64,
}

/// `fmod(360 + a, 360)`, as `Camera.cc`'s `wrap`.
fn wrap(a: f64) -> f64 {
    (360.0 + a) % 360.0
}

impl Gimbal {
    fn from_vpr(translate: DVec3, rotate: DVec3, distance: f64) -> Gimbal {
        Gimbal {
            object_trans: -translate,
            object_rot: DVec3::new(wrap(90.0 - rotate.x), wrap(-rotate.y), wrap(-rotate.z)),
            distance,
        }
    }

    /// `Camera::setup` with six numbers.
    fn from_vector(eye: DVec3, center: DVec3) -> Gimbal {
        let dir = center - eye;
        let deg = |y: f64, x: f64| y.atan2(x).to_degrees();
        let rz = if dir.x == 0.0 && dir.y == 0.0 {
            if dir.z < 0.0 {
                0.0
            } else {
                180.0
            }
        } else {
            -deg(dir.y, dir.x) + 90.0
        };
        let rx = -deg(dir.z, dir.truncate().length());
        Gimbal {
            object_trans: -center,
            object_rot: DVec3::new(rx, 0.0, rz),
            distance: dir.length(),
        }
    }

    /// `Camera::viewAll`.
    fn view_all(&mut self, bounds: &Aabb, autocenter: bool) {
        if bounds.is_empty() || !bounds.is_bounded() {
            self.object_trans = DVec3::ZERO;
            self.distance = DEFAULT_DISTANCE;
            return;
        }
        if autocenter {
            self.object_trans = -bounds.center();
        }
        let radius = (bounds.center() + self.object_trans).length()
            + 0.5 * (bounds.max - bounds.min).length();
        self.distance = radius / (0.5 * FOV_Y).to_radians().sin();
    }

    /// The world's eye, centre and up: the view `gluLookAt((0, −d, 0),
    /// 0, z)` after `glRotated` about x, y and z, turned back.
    fn camera(&self, width: u32, height: u32, projection: Projection) -> CameraSpec {
        let r = self.object_rot;
        let turn = DMat3::from_rotation_x(r.x.to_radians())
            * DMat3::from_rotation_y(r.y.to_radians())
            * DMat3::from_rotation_z(r.z.to_radians());
        let back = turn.transpose();
        let center = -self.object_trans;
        let tan_y = (0.5 * FOV_Y).to_radians().tan();
        let fov = 2.0 * (tan_y * width as f64 / height as f64).atan().to_degrees();
        CameraSpec {
            eye: center + back * DVec3::new(0.0, -self.distance, 0.0),
            lookat: center,
            up: back * DVec3::Z,
            fov,
            projection,
        }
    }
}

impl Viewpoint {
    /// The same view as `$vpt`, `$vpr` and `$vpd` (the eye-and-centre form
    /// turned into OpenSCAD's gimbal, as `Camera::setup` does).
    pub fn as_gimbal(self) -> Viewpoint {
        match self {
            Viewpoint::Vector { eye, center } => {
                let g = Gimbal::from_vector(eye, center);
                Viewpoint::Gimbal {
                    translate: -g.object_trans,
                    rotate: DVec3::new(90.0 - g.object_rot.x, -g.object_rot.y, -g.object_rot.z),
                    distance: g.distance,
                }
            }
            gimbal => gimbal,
        }
    }
}

/// OpenSCAD's interactive "View All" (`QGLView::viewAll`, which turns
/// `autocenter` on): the viewpoint turned by `rotate` (`$vpr`) that looks
/// at the centre of `bounds` from as far as `--viewall` moves back.
pub fn view_all(rotate: DVec3, bounds: &Aabb) -> Viewpoint {
    let mut g = Gimbal::from_vpr(DVec3::ZERO, rotate, DEFAULT_DISTANCE);
    g.view_all(bounds, true);
    Viewpoint::Gimbal {
        translate: -g.object_trans,
        rotate,
        distance: g.distance,
    }
}

/// The camera OpenSCAD would export a `width`×`height` PNG with, for a
/// scene whose box is `bounds`.
pub fn camera(opts: &ViewOptions, bounds: &Aabb, width: u32, height: u32) -> CameraSpec {
    let (mut g, viewall, autocenter) = match opts.camera {
        Some(Viewpoint::Gimbal {
            translate,
            rotate,
            distance,
        }) => (
            Gimbal::from_vpr(translate, rotate, distance),
            opts.viewall,
            opts.autocenter,
        ),
        Some(Viewpoint::Vector { eye, center }) => (
            Gimbal::from_vector(eye, center),
            opts.viewall,
            opts.autocenter,
        ),
        None => (
            Gimbal::from_vpr(DVec3::ZERO, DEFAULT_ROTATION, DEFAULT_DISTANCE),
            true,
            true,
        ),
    };
    // As in `export_png.cc`: only `viewall` moves the camera; `autocenter`
    // is how it does so.
    if viewall {
        g.view_all(bounds, autocenter);
    }
    g.camera(width, height, opts.projection.unwrap_or_default())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The eye-and-centre form as a gimbal is the same camera: the eye
    /// and centre where they were, up the same.
    #[test]
    fn an_eye_and_centre_is_the_same_view_as_a_gimbal() {
        for (eye, center) in [
            (DVec3::new(30.0, -40.0, 25.0), DVec3::new(1.0, 2.0, 3.0)),
            (DVec3::new(-5.0, 7.0, -9.0), DVec3::ZERO),
            (DVec3::new(0.5, 80.0, 0.0), DVec3::new(0.5, 0.0, 0.0)),
        ] {
            let cam = |v: Viewpoint| {
                let opts = ViewOptions {
                    camera: Some(v),
                    ..Default::default()
                };
                camera(&opts, &Aabb::EMPTY, 800, 600)
            };
            let v = Viewpoint::Vector { eye, center };
            let (a, b) = (cam(v), cam(v.as_gimbal()));
            assert!(matches!(v.as_gimbal(), Viewpoint::Gimbal { .. }));
            for (p, q) in [(a.eye, b.eye), (a.lookat, b.lookat), (a.up, b.up)] {
                assert!((p - q).length() < 1e-9, "{p} {q}");
            }
            assert!((a.eye - eye).length() < 1e-9 && (a.lookat - center).length() < 1e-9);
        }
    }

    #[test]
    fn parse_forms() {
        assert!(matches!(
            Viewpoint::parse("1,2,3,4,5,6,7"),
            Ok(Viewpoint::Gimbal { distance, .. }) if distance == 7.0
        ));
        assert!(matches!(
            Viewpoint::parse("1,2,3,4,5,6"),
            Ok(Viewpoint::Vector { .. })
        ));
        for bad in [
            "1,2,3",
            "1,2,3,4,5,6,7,8",
            "a,b,c,d,e,f",
            "0,0,0,0,0,0",
            "0,0,0,0,0,0,-1",
            "1,2,3,nan,5,6",
        ] {
            assert!(Viewpoint::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn default_view_is_openscads_direction() {
        // $vpr = [55, 0, 25] looks at the origin from front-right-above,
        // the direction csgrt's own framing uses.
        let c = camera(&ViewOptions::default(), &Aabb::EMPTY, 4, 3);
        let dir = (c.eye - c.lookat).normalize();
        assert!((dir - super::super::defaults::view_direction()).length() < 1e-12);
        assert!(((c.eye - c.lookat).length() - DEFAULT_DISTANCE).abs() < 1e-9);
    }
}
