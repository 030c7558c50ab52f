//! OpenSCAD's command-line camera (`--camera` in both forms, `--viewall`,
//! `--autocenter`, `--projection`), checked against OpenGL's own pipeline
//! written out here from the GL specification: OpenSCAD 2021.01's
//! `GLView::setupCamera` is `gluPerspective(fov, aspect)` (or `glOrtho` of
//! half-height `dist·tan(fov/2)`), `gluLookAt((0, −dist, 0), 0, z)`, then
//! `glRotated` about x, y, z by `object_rot` and `glTranslated` by
//! `object_trans` (`Camera.cc`: `object_rot` = 90 − rx, −ry, −rz;
//! `object_trans` = −t; `viewAll`: dist = radius / sin(fov/2)).
//!
//! Small balls are put at known points; each ball's blob in csgrt's hit
//! mask must be centred where that pipeline projects the ball's centre.
//! The same options were compared with OpenSCAD's own PNG export by
//! `tools/dev/openscad_view.py`.

use crate::common;
use crate::common::csgrt;

const W: usize = 320;
const H: usize = 240;
const R: f64 = 0.4;
const POINTS: [[f64; 3]; 4] = [
    [10.0, -4.0, 7.0],
    [-5.0, 2.0, -3.0],
    [0.0, 0.0, 0.0],
    [4.0, 6.0, -2.0],
];

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            m[i][j] = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

fn apply(m: &M4, p: [f64; 3]) -> [f64; 4] {
    let v = [p[0], p[1], p[2], 1.0];
    let mut o = [0.0; 4];
    for i in 0..4 {
        o[i] = (0..4).map(|k| m[i][k] * v[k]).sum();
    }
    o
}

/// `glRotated(deg, axis)` for a unit axis (GL spec, 2.11.2).
fn rotated(deg: f64, [x, y, z]: [f64; 3]) -> M4 {
    let (s, c) = deg.to_radians().sin_cos();
    let t = 1.0 - c;
    [
        [x * x * t + c, x * y * t - z * s, x * z * t + y * s, 0.0],
        [y * x * t + z * s, y * y * t + c, y * z * t - x * s, 0.0],
        [x * z * t - y * s, y * z * t + x * s, z * z * t + c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn translated([x, y, z]: [f64; 3]) -> M4 {
    [
        [1.0, 0.0, 0.0, x],
        [0.0, 1.0, 0.0, y],
        [0.0, 0.0, 1.0, z],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// `gluLookAt((0, −d, 0), (0, 0, 0), (0, 0, 1))`: f = +y, s = f × up = +x,
/// u = s × f = +z; rows s, u, −f, then the eye moved to the origin.
fn look_at(d: f64) -> M4 {
    let m = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    mul(&m, &translated([0.0, d, 0.0]))
}

struct Gl {
    rot: [f64; 3],
    trans: [f64; 3],
    dist: f64,
    fov: f64,
    ortho: bool,
}

impl Gl {
    /// The window position (pixels from the top left) of `p`.
    fn project(&self, p: [f64; 3]) -> (f64, f64) {
        let mut mv = look_at(self.dist);
        mv = mul(&mv, &rotated(self.rot[0], [1.0, 0.0, 0.0]));
        mv = mul(&mv, &rotated(self.rot[1], [0.0, 1.0, 0.0]));
        mv = mul(&mv, &rotated(self.rot[2], [0.0, 0.0, 1.0]));
        mv = mul(&mv, &translated(self.trans));
        let e = apply(&mv, p);
        let aspect = W as f64 / H as f64;
        let half = (0.5 * self.fov).to_radians().tan();
        let (nx, ny) = if self.ortho {
            let h = self.dist * half;
            (e[0] / (h * aspect), e[1] / h)
        } else {
            // gluPerspective: x_clip = (f/aspect)·x, y_clip = f·y, w = −z.
            let f = 1.0 / half;
            (f / aspect * e[0] / -e[2], f * e[1] / -e[2])
        };
        ((nx + 1.0) * 0.5 * W as f64, (1.0 - ny) * 0.5 * H as f64)
    }

    /// `Camera::setVpt`, `setVpr`, `viewer_distance` of `--camera` with 7
    /// numbers.
    fn gimbal(t: [f64; 3], r: [f64; 3], dist: f64) -> Gl {
        let wrap = |a: f64| (360.0 + a) % 360.0;
        Gl {
            rot: [wrap(90.0 - r[0]), wrap(-r[1]), wrap(-r[2])],
            trans: [-t[0], -t[1], -t[2]],
            dist,
            fov: 22.5,
            ortho: false,
        }
    }

    /// `Camera::setup` with 6 numbers.
    fn vector(eye: [f64; 3], c: [f64; 3]) -> Gl {
        let d = [c[0] - eye[0], c[1] - eye[1], c[2] - eye[2]];
        let rz = if d[0] == 0.0 && d[1] == 0.0 {
            if d[2] < 0.0 {
                0.0
            } else {
                180.0
            }
        } else {
            -d[1].atan2(d[0]).to_degrees() + 90.0
        };
        let rx = -d[2].atan2(d[0].hypot(d[1])).to_degrees();
        Gl {
            rot: [rx, 0.0, rz],
            trans: [-c[0], -c[1], -c[2]],
            dist: (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt(),
            fov: 22.5,
            ortho: false,
        }
    }

    /// `Camera::viewAll` on the balls' box.
    fn view_all(mut self, autocenter: bool) -> Gl {
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for p in POINTS {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k] - R);
                hi[k] = hi[k].max(p[k] + R);
            }
        }
        let c: Vec<f64> = (0..3).map(|k| 0.5 * (lo[k] + hi[k])).collect();
        if autocenter {
            self.trans = [-c[0], -c[1], -c[2]];
        }
        let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        let off = (0..3)
            .map(|k| (c[k] + self.trans[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        self.dist = (off + 0.5 * diag) / (0.5 * self.fov).to_radians().sin();
        self
    }
}

/// The balls as OpenSCAD exports them, with an optional csgrt camera.
fn model(camera: &str) -> String {
    let mut s = camera.to_string();
    for [x, y, z] in POINTS {
        s += &format!(
            "multmatrix([[1, 0, 0, {x}], [0, 1, 0, {y}], [0, 0, 1, {z}], [0, 0, 0, 1]]) {{\n\tsphere($fn = 0, $fa = 12, $fs = 2, r = {R});\n}}\n"
        );
    }
    s
}

/// The centre of each ball's blob in the mask, matched to the nearest
/// expected position; returns the largest miss in pixels.
fn worst_miss(file_camera: &str, args: &[&str], expect: &dyn Fn([f64; 3]) -> (f64, f64)) -> f64 {
    let (dir, _) = common::scene("b.csg", &model(file_camera));
    let mut all = vec!["b.csg", "--size", "320x240", "-q", "--mask", "m.png"];
    all.extend_from_slice(args);
    let r = csgrt(dir.path(), &all);
    assert_eq!(r.status, 0, "{}", r.stderr);
    let mask = image::open(dir.path().join("m.png")).unwrap().to_luma8();
    let want: Vec<(f64, f64)> = POINTS.iter().map(|&p| expect(p)).collect();
    for &(x, y) in &want {
        assert!(
            x > 4.0 && x < W as f64 - 4.0 && y > 4.0 && y < H as f64 - 4.0,
            "a ball is expected off the image at ({x}, {y}); choose another view"
        );
    }
    let mut sums = vec![(0.0, 0.0, 0usize); want.len()];
    for (x, y, p) in mask.enumerate_pixels() {
        if p[0] == 0 {
            continue;
        }
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let near = (0..want.len())
            .min_by(|&a, &b| {
                let da = (want[a].0 - cx).hypot(want[a].1 - cy);
                let db = (want[b].0 - cx).hypot(want[b].1 - cy);
                da.total_cmp(&db)
            })
            .unwrap();
        sums[near].0 += cx;
        sums[near].1 += cy;
        sums[near].2 += 1;
    }
    let mut worst: f64 = 0.0;
    for (s, w) in sums.iter().zip(&want) {
        assert!(s.2 >= 3, "a ball covers {} pixels near {w:?}", s.2);
        let c = (s.0 / s.2 as f64, s.1 / s.2 as f64);
        worst = worst.max((c.0 - w.0).hypot(c.1 - w.1));
    }
    worst
}

/// A blob's centroid from pixel centres is within this of the true centre
/// of a ball of a few pixels across (measured: at most 0.25).
const TOL: f64 = 0.35;

#[test]
fn gimbal_camera_is_openscads() {
    let gl = Gl::gimbal([3.0, 1.0, 2.0], [60.0, 0.0, 35.0], 60.0);
    let miss = worst_miss("", &["--camera=3,1,2,60,0,35,60"], &|p| gl.project(p));
    assert!(miss < TOL, "{miss}");
    // A roll about y too, and the numbers given as a separate argument.
    let gl = Gl::gimbal([1.0, -2.0, 0.5], [70.0, 20.0, -140.0], 50.0);
    let miss = worst_miss("", &["--camera", "1,-2,0.5,70,20,-140,50"], &|p| {
        gl.project(p)
    });
    assert!(miss < TOL, "{miss}");
}

#[test]
fn vector_camera_is_openscads() {
    let gl = Gl::vector([40.0, -50.0, 30.0], [2.0, 1.0, 0.0]);
    let miss = worst_miss("", &["--camera=40,-50,30,2,1,0"], &|p| gl.project(p));
    assert!(miss < TOL, "{miss}");
    // Straight down: OpenSCAD's own special case.
    let gl = Gl::vector([1.0, 1.0, 70.0], [1.0, 1.0, 0.0]);
    let miss = worst_miss("", &["--camera=1,1,70,1,1,0"], &|p| gl.project(p));
    assert!(miss < TOL, "{miss}");
}

#[test]
fn orthographic_camera_is_openscads() {
    let mut gl = Gl::gimbal([3.0, 1.0, 2.0], [60.0, 0.0, 35.0], 60.0);
    gl.ortho = true;
    let miss = worst_miss(
        "",
        &["--camera=3,1,2,60,0,35,60", "--projection=ortho"],
        &|p| gl.project(p),
    );
    assert!(miss < TOL, "{miss}");
}

#[test]
fn viewall_and_autocenter_are_openscads() {
    // No --camera: OpenSCAD's default view, fitted and centred.
    let gl = Gl::gimbal([0.0; 3], [55.0, 0.0, 25.0], 140.0).view_all(true);
    for args in [
        &["--viewall"][..],
        &["--autocenter"],
        &["--viewall", "--autocenter"],
    ] {
        let miss = worst_miss("", args, &|p| gl.project(p));
        assert!(miss < TOL, "{args:?}: {miss}");
    }
    // With --camera: --viewall keeps the centre, --autocenter moves it.
    let gl = Gl::gimbal([3.0, 1.0, 2.0], [60.0, 0.0, 35.0], 10.0).view_all(false);
    let miss = worst_miss("", &["--camera=3,1,2,60,0,35,10", "--viewall"], &|p| {
        gl.project(p)
    });
    assert!(miss < TOL, "{miss}");
    let mut gl = Gl::gimbal([3.0, 1.0, 2.0], [60.0, 0.0, 35.0], 10.0).view_all(true);
    gl.ortho = true;
    let miss = worst_miss(
        "",
        &[
            "--camera=3,1,2,60,0,35,10",
            "--viewall",
            "--autocenter",
            "--projection=o",
        ],
        &|p| gl.project(p),
    );
    assert!(miss < TOL, "{miss}");
}

#[test]
fn camera_option_overrides_the_files_camera() {
    let file = "camera(eye = [0, -80, 0], lookat = [0, 0, 0]);\n";
    let gl = Gl::gimbal([3.0, 1.0, 2.0], [60.0, 0.0, 35.0], 60.0);
    let miss = worst_miss(file, &["--camera=3,1,2,60,0,35,60"], &|p| gl.project(p));
    assert!(miss < TOL, "{miss}");
}

#[test]
fn projection_alone_keeps_the_files_camera() {
    // The file's camera, seen with parallel rays: the plane through
    // `lookat` square to the view keeps its scale, 2·60·tan(40°/2) wide.
    let file = "camera(eye = [0, -60, 0], lookat = [0, 0, 0], fov = 40);\n";
    let wide = 2.0 * 60.0 * 20f64.to_radians().tan();
    let px = W as f64 / wide;
    let expect = |p: [f64; 3]| (0.5 * W as f64 + p[0] * px, 0.5 * H as f64 - p[2] * px);
    let miss = worst_miss(file, &["--projection", "orthogonal"], &expect);
    assert!(miss < TOL, "{miss}");
    // And with perspective the same file is not orthographic.
    let miss = worst_miss(file, &["--projection", "p"], &expect);
    assert!(miss > 1.0, "{miss}");
}

#[test]
fn bad_camera_options_are_refused() {
    let (dir, _) = common::scene("b.csg", &model(""));
    for args in [
        &["b.csg", "--camera=1,2,3"][..],
        &["b.csg", "--camera=1,2,3,4,5,6,0"],
        &["b.csg", "--camera=0,0,0,0,0,0"],
        &["b.csg", "--camera=1,2,x,4,5,6"],
        &["b.csg", "--projection=fisheye"],
    ] {
        let r = csgrt(dir.path(), args);
        assert_eq!(r.status, 2, "{args:?}: {}", r.stderr);
        assert!(
            r.stderr.contains("expected") || r.stderr.contains("must"),
            "{}",
            r.stderr
        );
        assert!(!dir.path().join("b.png").exists());
    }
}
