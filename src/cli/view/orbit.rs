//! The viewer's camera, moved as OpenSCAD 2021.01's GUI moves its own
//! (`QGLView.cc`: `mouseMoveEvent`, `wheelEvent`, `translate`, `rotate`;
//! `Camera.cc`: `zoom`, `resetView`; `mainwin.cc`: the view menu), kept as
//! the seven numbers of `--camera tx,ty,tz,rx,ry,rz,dist` (`$vpt`, `$vpr`,
//! `$vpd`) and a projection: the picture is always the one those numbers
//! give on the command line, bit for bit, because the command line is
//! read back into the same numbers (Rust prints an `f64` as the shortest
//! text that parses to it).
//!
//! OpenSCAD turns its gimbal's `object_rot`, which is (90° − `$vpr`.x,
//! −`$vpr`.y, −`$vpr`.z) and `object_trans`, which is −`$vpt`: a drag that
//! adds to `object_rot` subtracts from `$vpr` here.

use csgrt::geometry::Aabb;
use csgrt::scene::openscad_view::{self, Viewpoint, DEFAULT_DISTANCE, DEFAULT_ROTATION};
use csgrt::scene::{CameraSpec, Projection};
use glam::{DMat3, DVec3};

/// OpenSCAD's degrees (and pan units) per pixel a drag moves.
const DRAG: f64 = 0.7;
/// The wheel's unit: one notch (Qt's `angleDelta`).
pub const NOTCH: f64 = 120.0;

/// Which of OpenSCAD's view commands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewKey {
    Top,
    Bottom,
    Left,
    Right,
    Front,
    Back,
    Diagonal,
    Center,
    ViewAll,
    Reset,
    ZoomIn,
    ZoomOut,
    Perspective,
    Orthogonal,
}

/// The view: `--camera`'s seven numbers and `--projection`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    pub translate: DVec3,
    /// Degrees, each in [0°, 360°).
    pub rotate: DVec3,
    pub distance: f64,
    pub projection: Projection,
}

/// An angle in [0°, 360°).
fn turn(a: f64) -> f64 {
    let r = a.rem_euclid(360.0);
    // (rem_euclid of a tiny negative angle rounds to 360 itself; −0 is
    // written 0.)
    if r >= 360.0 || r == 0.0 {
        0.0
    } else {
        r
    }
}

impl Orbit {
    /// The view a picture starts from: `given` (`--camera`, or the
    /// program's `$vp*`), else OpenSCAD's reset view moved to see all of
    /// `bounds`, as OpenSCAD's first preview does.
    pub fn start(given: Option<Viewpoint>, bounds: &Aabb, projection: Projection) -> Orbit {
        let mut o = Orbit {
            translate: DVec3::ZERO,
            rotate: DEFAULT_ROTATION,
            distance: DEFAULT_DISTANCE,
            projection,
        };
        match given {
            Some(v) => o.set(v.as_gimbal()),
            None => o.set(openscad_view::view_all(o.rotate, bounds)),
        }
        o
    }

    fn set(&mut self, v: Viewpoint) {
        if let Viewpoint::Gimbal {
            translate,
            rotate,
            distance,
        } = v
        {
            self.translate = translate;
            self.rotate = rotate.map(turn);
            self.distance = distance;
        }
    }

    /// The viewpoint as `--camera` reads it.
    pub fn viewpoint(&self) -> Viewpoint {
        Viewpoint::Gimbal {
            translate: self.translate,
            rotate: self.rotate,
            distance: self.distance,
        }
    }

    /// The camera of a `width`×`height` picture: `--camera`'s, through the
    /// same function the command line calls.
    pub fn camera(&self, width: u32, height: u32) -> CameraSpec {
        let opts = openscad_view::ViewOptions {
            camera: Some(self.viewpoint()),
            viewall: false,
            autocenter: false,
            projection: Some(self.projection),
        };
        openscad_view::camera(&opts, &Aabb::EMPTY, width, height)
    }

    /// `--camera tx,ty,tz,rx,ry,rz,dist`'s value.
    pub fn camera_arg(&self) -> String {
        let (t, r) = (self.translate, self.rotate);
        format!(
            "{},{},{},{},{},{},{}",
            t.x, t.y, t.z, r.x, r.y, r.z, self.distance
        )
    }

    /// A left drag of (dx, dy) pixels: about the view's x and the world's z
    /// axis (with shift, the view's y), 0.7° a pixel.
    pub fn rotate_by(&mut self, dx: f64, dy: f64, shift: bool) {
        let (dx, dy) = (dx * DRAG, dy * DRAG);
        let mut r = self.rotate;
        r.x -= dy;
        if shift {
            r.y -= dx;
        } else {
            r.z -= dx;
        }
        self.rotate = r.map(turn);
    }

    /// A right drag (`middle`: a middle drag) of (dx, dy) pixels in a
    /// window `width`×`height`: the view moves across the screen (the
    /// middle button: in and out along the line of sight); with shift, a
    /// zoom.
    pub fn pan_by(&mut self, dx: f64, dy: f64, middle: bool, shift: bool, width: u32, height: u32) {
        let (dx, dy) = (dx * DRAG, dy * DRAG);
        if shift {
            self.zoom_by(-12.0 * dy);
            return;
        }
        let mut m = DVec3::new(
            dx * 3.0 * self.distance / width.max(1) as f64,
            0.0,
            -dy * 3.0 * self.distance / height.max(1) as f64,
        );
        if middle {
            m = DVec3::new(0.0, m.z, 0.0);
        }
        self.move_by(m);
    }

    /// `QGLView::translate` relative to the viewport: m along the view's
    /// right, depth and up; `object_trans += Rz·Ry·Rx·m`, the rotations
    /// by −object_rot.
    fn move_by(&mut self, m: DVec3) {
        let o = self.object_rot();
        let turn = DMat3::from_rotation_z(-o.z.to_radians())
            * DMat3::from_rotation_y(-o.y.to_radians())
            * DMat3::from_rotation_x(-o.x.to_radians());
        self.translate -= turn * m;
    }

    /// The wheel at pixel (x, y) of a `width`×`height` window: OpenSCAD's
    /// mouse-centric zoom (`QGLView::zoomCursor`, on by default in
    /// 2021.01): [`Orbit::zoom_by`], and the view moved so that the point
    /// of the plane through the centre under the cursor stays under it.
    pub fn zoom_at(&mut self, v: f64, x: f64, y: f64, width: u32, height: u32) {
        let (w, h) = (width.max(1) as f64, height.max(1) as f64);
        let old = self.distance;
        self.zoom_by(v);
        let ratio = old / self.distance - 1.0;
        let sx = 2.0 * (x + 0.5) / w - 1.0;
        let sy = 1.0 - 2.0 * (y + 0.5) / h;
        let half = self.distance * (0.5 * openscad_view::FOV_Y).to_radians().tan();
        let (mx, mz) = (ratio * sx * (w / h) * half, ratio * sy * half);
        self.move_by(DVec3::new(-mx, 0.0, -mz));
    }

    /// `Camera::zoom`: the distance times 0.9 for each notch (`v` = 120).
    pub fn zoom_by(&mut self, v: f64) {
        let d = self.distance * 0.9f64.powf(v / NOTCH);
        // A distance of 0 or ∞ has no view back: the last one is kept.
        if d.is_finite() && d > 0.0 {
            self.distance = d;
        }
    }

    /// OpenSCAD's `object_rot` of this view.
    fn object_rot(&self) -> DVec3 {
        DVec3::new(90.0 - self.rotate.x, -self.rotate.y, -self.rotate.z)
    }

    fn set_object_rot(&mut self, o: DVec3) {
        self.rotate = DVec3::new(90.0 - o.x, -o.y, -o.z).map(turn);
    }

    /// One of OpenSCAD's view commands; `bounds` is what View All sees.
    pub fn key(&mut self, k: ViewKey, bounds: &Aabb) {
        match k {
            ViewKey::Top => self.set_object_rot(DVec3::new(90.0, 0.0, 0.0)),
            ViewKey::Bottom => self.set_object_rot(DVec3::new(270.0, 0.0, 0.0)),
            ViewKey::Left => self.set_object_rot(DVec3::new(0.0, 0.0, 90.0)),
            ViewKey::Right => self.set_object_rot(DVec3::new(0.0, 0.0, 270.0)),
            ViewKey::Front => self.set_object_rot(DVec3::ZERO),
            ViewKey::Back => self.set_object_rot(DVec3::new(0.0, 0.0, 180.0)),
            ViewKey::Diagonal => self.set_object_rot(DVec3::new(35.0, 0.0, -25.0)),
            ViewKey::Center => self.translate = DVec3::ZERO,
            ViewKey::ViewAll => self.set(openscad_view::view_all(self.rotate, bounds)),
            ViewKey::Reset => {
                self.rotate = DEFAULT_ROTATION;
                self.translate = DVec3::ZERO;
                self.distance = DEFAULT_DISTANCE;
            }
            ViewKey::ZoomIn => self.zoom_by(NOTCH),
            ViewKey::ZoomOut => self.zoom_by(-NOTCH),
            ViewKey::Perspective => self.projection = Projection::Perspective,
            ViewKey::Orthogonal => self.projection = Projection::Orthographic,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn orbit() -> Orbit {
        Orbit {
            translate: DVec3::new(1.5, -2.0, 3.25),
            rotate: DVec3::new(55.0, 0.0, 25.0),
            distance: 140.0,
            projection: Projection::Perspective,
        }
    }

    /// The printed `--camera` parses back to the same numbers, bit for
    /// bit, whatever drags brought them to (the picture's identity with
    /// the command line rests on it).
    #[test]
    fn the_printed_camera_reads_back_to_the_same_numbers() {
        let mut o = orbit();
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0
        };
        for i in 0..500 {
            match i % 4 {
                0 => o.rotate_by(next(), next(), i % 8 == 0),
                1 => o.pan_by(next(), next(), i % 3 == 0, false, 800, 600),
                2 => o.zoom_by(next()),
                _ => o.pan_by(next(), next(), false, true, 640, 480),
            }
            match Viewpoint::parse(&o.camera_arg()) {
                Ok(v) => assert_eq!(v, o.viewpoint(), "{}", o.camera_arg()),
                Err(e) => panic!("{e}"),
            }
            assert!(o.rotate.cmpge(DVec3::ZERO).all() && o.rotate.cmplt(DVec3::splat(360.0)).all());
        }
    }

    /// A left drag turns as OpenSCAD's does: down by y pixels tilts
    /// `object_rot`.x by 0.7·y degrees, so `$vpr`.x by −0.7·y; across by x
    /// turns about z (with shift, about y).
    #[test]
    fn drags_and_the_wheel_move_as_openscads() {
        let mut o = orbit();
        o.rotate_by(10.0, 20.0, false);
        assert!((o.rotate - DVec3::new(55.0 - 14.0, 0.0, 25.0 - 7.0)).length() < 1e-12);
        o.rotate_by(10.0, 0.0, true);
        assert!((o.rotate - DVec3::new(41.0, 353.0, 18.0)).length() < 1e-12);
        // Two notches in: 0.81 of the distance; one out undoes one.
        let mut z = orbit();
        z.zoom_by(2.0 * NOTCH);
        assert!((z.distance - 140.0 * 0.81).abs() < 1e-12);
        z.zoom_by(-NOTCH);
        assert!((z.distance - 140.0 * 0.9).abs() < 1e-12);
        // Front view (object_rot 0): a right drag to the right moves the
        // centre left along x by 0.7·3·d/width a pixel, and up moves it
        // down along z; the middle button moves along y (depth).
        let mut p = orbit();
        p.key(ViewKey::Front, &Aabb::EMPTY);
        assert_eq!(p.rotate, DVec3::new(90.0, 0.0, 0.0));
        let before = p.translate;
        p.pan_by(100.0, -50.0, false, false, 800, 600);
        let moved = p.translate - before;
        let k = 0.7 * 3.0 * 140.0;
        assert!((moved - DVec3::new(-100.0 * k / 800.0, 0.0, -50.0 * k / 600.0)).length() < 1e-9);
        let before = p.translate;
        p.pan_by(0.0, -50.0, true, false, 800, 600);
        assert!((p.translate - before - DVec3::new(0.0, -50.0 * k / 600.0, 0.0)).length() < 1e-9);
    }

    /// The wheel zooms about the cursor: the point of the plane through
    /// the centre under pixel (x, y) is under it after the zoom, in
    /// either projection.
    #[test]
    fn the_wheel_zooms_about_the_cursor() {
        use csgrt::render::camera::Camera;
        for projection in [Projection::Perspective, Projection::Orthographic] {
            for (x, y, v) in [
                (100.0, 80.0, NOTCH),
                (700.0, 500.0, -2.0 * NOTCH),
                (399.5, 299.5, NOTCH),
            ] {
                let mut o = orbit();
                o.projection = projection;
                o.rotate_by(30.0, -20.0, false);
                let before = Camera::new(&o.camera(800, 600), 800, 600);
                let spec = o.camera(800, 600);
                let ray = before.ray(x + 0.5, y + 0.5);
                let ahead = (spec.lookat - spec.eye).normalize();
                let t = (spec.lookat - ray.origin).dot(ahead) / ray.dir.dot(ahead);
                let p = ray.origin + ray.dir * t;
                o.zoom_at(v, x, y, 800, 600);
                let (px, py, _) = Camera::new(&o.camera(800, 600), 800, 600).project(p);
                assert!(
                    (px - x - 0.5).abs() < 1e-6 && (py - y - 0.5).abs() < 1e-6,
                    "{px} {py}"
                );
                assert!((o.distance - 140.0 * 0.9f64.powf(v / NOTCH)).abs() < 1e-9);
            }
        }
    }

    /// The view keys give OpenSCAD's `object_rot` (`mainwin.cc`) and its
    /// camera: the top view looks down −z, the front view along +y.
    #[test]
    fn the_view_keys_look_where_openscads_do() {
        let b = Aabb::new(DVec3::new(-1.0, -2.0, -3.0), DVec3::new(5.0, 4.0, 3.0));
        let look = |k: ViewKey| {
            let mut o = orbit();
            o.key(ViewKey::Center, &b);
            o.key(k, &b);
            let c = o.camera(800, 600);
            (c.lookat - c.eye).normalize()
        };
        let near = |a: DVec3, b: DVec3| (a - b).length() < 1e-12;
        assert!(near(look(ViewKey::Top), -DVec3::Z));
        assert!(near(look(ViewKey::Bottom), DVec3::Z));
        assert!(near(look(ViewKey::Front), DVec3::Y));
        assert!(near(look(ViewKey::Back), -DVec3::Y));
        assert!(near(look(ViewKey::Right), -DVec3::X));
        assert!(near(look(ViewKey::Left), DVec3::X));
        // View All looks at the box's centre from OpenSCAD's distance:
        // the half diagonal over sin(11.25°).
        let mut o = orbit();
        o.key(ViewKey::ViewAll, &b);
        assert_eq!(o.translate, b.center());
        let want = 0.5 * (b.max - b.min).length() / 11.25f64.to_radians().sin();
        assert!((o.distance - want).abs() < 1e-9 * want);
        o.key(ViewKey::Reset, &b);
        assert_eq!(
            (o.translate, o.rotate, o.distance),
            (DVec3::ZERO, DEFAULT_ROTATION, 140.0)
        );
        o.key(ViewKey::Orthogonal, &b);
        assert_eq!(o.camera(10, 10).projection, Projection::Orthographic);
    }
}
