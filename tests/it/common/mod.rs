//! Helpers for running the csgrt binary in a scratch folder.
#![allow(dead_code)]

use csgrt::geometry::{Cuboid, Shape, Sphere};
use glam::{DAffine3, DQuat, DVec3};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub struct Run {
    pub status: i32,
    pub stdout: String,
    pub stderr: String,
}

pub fn csgrt(dir: &Path, args: &[&str]) -> Run {
    csgrt_stdin(dir, args, None)
}

pub fn csgrt_stdin(dir: &Path, args: &[&str], stdin: Option<&str>) -> Run {
    csgrt_env(dir, args, stdin, &[])
}

/// [`csgrt_stdin`] with these environment variables set.
pub fn csgrt_env(
    dir: &Path,
    args: &[&str],
    stdin: Option<&str>,
    vars: &[(&str, &std::ffi::OsStr)],
) -> Run {
    use std::io::Write;
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_csgrt"));
    cmd.current_dir(dir).args(args);
    for (k, v) in vars {
        cmd.env(k, v);
    }
    cmd.stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    let mut child = cmd.spawn().expect("csgrt runs");
    if let Some(s) = stdin {
        child.stdin.take().unwrap().write_all(s.as_bytes()).unwrap();
    }
    drop(child.stdin.take());
    let Output {
        status,
        stdout,
        stderr,
    } = child.wait_with_output().unwrap();
    Run {
        status: status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&stdout).into_owned(),
        stderr: String::from_utf8_lossy(&stderr).into_owned(),
    }
}

/// Runs csgrt in `dir` with PATH set to `path` only.
#[cfg(unix)]
pub fn csgrt_with_path(
    dir: &std::path::Path,
    path: &std::path::Path,
    args: &[&str],
) -> (i32, String) {
    let r = csgrt_env(dir, args, None, &[("PATH", path.as_os_str())]);
    (r.status, r.stderr)
}

/// A stand-in `openscad` in its own folder: `body` is its shell script.
#[cfg(unix)]
pub fn fake_openscad(body: &str) -> tempfile::TempDir {
    use std::os::unix::fs::PermissionsExt;
    let bin = tempfile::tempdir().unwrap();
    let p = bin.path().join("openscad");
    std::fs::write(&p, format!("#!/bin/sh\n{body}\n")).unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
    bin
}

/// Runs csgrt in `dir` with `args` and checks that it refused them: exit
/// status 2, `says` in its message, and `dir` holding exactly `files`
/// (sorted) afterwards.
pub fn refused(dir: &Path, args: &[&str], says: &str, files_after: &[&str]) {
    let r = csgrt(dir, args);
    assert_eq!(r.status, 2, "{args:?}: {}", r.stderr);
    assert!(r.stderr.contains(says), "{args:?}: {}", r.stderr);
    assert_eq!(files(dir), files_after, "{args:?}");
}

/// A fresh scratch folder holding `name` with `text`.
pub fn scene(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

/// Runs a bad scene `bad.csg` and returns stderr, checking exit 2 and that
/// no output file was left.
pub fn fails(text: &str) -> String {
    let (dir, _) = scene("bad.csg", text);
    let r = csgrt(dir.path(), &["bad.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert_eq!(files(dir.path()), ["bad.csg"], "no output may be left");
    r.stderr
}

/// Runs `bad.csg`, a scene OpenSCAD renders with a warning: csgrt warns
/// and renders it, exit 0, to the same image as `without` (the scene with
/// the statement OpenSCAD leaves out taken out); under `--strict` the
/// warning is the error, exit 2, nothing written. Returns that stderr.
pub fn lenient(text: &str, without: &str) -> String {
    let (dir, _) = scene("bad.csg", text);
    std::fs::write(dir.path().join("good.csg"), without).unwrap();
    let run = |first: &[&str]| {
        let mut v = first.to_vec();
        v.extend(["--size", "16x12", "-q"]);
        csgrt(dir.path(), &v)
    };
    let strict = run(&["bad.csg", "--strict"]);
    assert_eq!(strict.status, 2, "{}", strict.stderr);
    assert_eq!(
        files(dir.path()),
        ["bad.csg", "good.csg"],
        "no output may be left"
    );
    let warned = run(&["bad.csg", "-o", "bad.png"]);
    assert_eq!(warned.status, 0, "{}", warned.stderr);
    assert!(warned.stderr.starts_with("warning: "), "{}", warned.stderr);
    let good = run(&["good.csg", "-o", "good.png"]);
    assert_eq!(good.status, 0, "{}", good.stderr);
    let read = |f: &str| std::fs::read(dir.path().join(f)).unwrap();
    assert!(
        read("bad.png") == read("good.png"),
        "{text} and {without} differ"
    );
    strict.stderr
}

/// The names of the files in a folder, sorted.
pub fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

pub fn stats(dir: &Path, file: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join(file)).unwrap()).unwrap()
}

/// A small deterministic generator (SplitMix64), so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    /// A uniform number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    /// A uniform unit vector.
    pub fn unit(&mut self) -> glam::DVec3 {
        loop {
            let v = glam::DVec3::new(self.next(), self.next(), self.next()) * 2.0 - 1.0;
            if (1e-3..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }
}

/// An L-shaped region with a triangular hole in its lower arm, as a prism
/// (a leaf that carries its region by reference) whose top section is
/// scaled by `top` (1: straight).
pub fn l_prism(top: f64) -> csgrt::geometry::Shape {
    csgrt::geometry::Shape::Prism(csgrt::geometry::Prism::new(
        std::sync::Arc::new(l_region()),
        top,
        top < 0.5,
    ))
}

/// The L region twisted by `twist` radians and scaled to `scale` at the
/// top (OpenSCAD's twisted or unevenly scaled linear_extrude).
pub fn l_twisted(twist: f64, scale: glam::DVec2) -> csgrt::geometry::Shape {
    csgrt::geometry::Shape::Twisted(csgrt::geometry::Twisted {
        section: csgrt::geometry::TwistSection::Region(std::sync::Arc::new(l_region())),
        twist,
        scale,
        centered: twist < 0.0,
    })
}

/// The same region moved off the axis and turned about it: a lathe.
pub fn l_lathe() -> csgrt::geometry::Shape {
    use csgrt::plane::{Outlines, Region};
    let moved = Outlines::polygons(
        l_region()
            .outlines
            .loops
            .iter()
            .map(|l| l.iter().map(|p| *p + glam::DVec2::new(0.5, -1.0)).collect())
            .collect(),
    );
    csgrt::geometry::Shape::Lathe(csgrt::geometry::Lathe::new(std::sync::Arc::new(
        Region::new(moved),
    )))
}

/// The L of two boxes, [0,2]×[0,1] ∪ [0,1]×[0,2], counter-clockwise.
pub const L_CORNERS: [(f64, f64); 6] = [
    (0.0, 0.0),
    (2.0, 0.0),
    (2.0, 1.0),
    (1.0, 1.0),
    (1.0, 2.0),
    (0.0, 2.0),
];

fn l_points() -> Vec<glam::DVec2> {
    L_CORNERS
        .iter()
        .map(|&(x, y)| glam::DVec2::new(x, y))
        .collect()
}

fn l_region() -> csgrt::plane::Region {
    use csgrt::plane::{Outlines, Region};
    let p = |x: f64, y: f64| glam::DVec2::new(x, y);
    let outlines = Outlines::polygons(vec![
        l_points(),
        vec![p(1.3, 0.2), p(1.8, 0.2), p(1.8, 0.7)],
    ]);
    Region::new(outlines)
}

/// A region bounded by curves, as a glyph is: a D whose bow is `bow` (a
/// cubic with an S-bend, crossed up to three times by a line, or a
/// quadratic) and whose top is a quadratic, with a lens-shaped hole of two
/// quadratics, moved by `shift`.
fn curved_region(
    bow: impl Fn(&dyn Fn(f64, f64) -> glam::DVec2) -> csgrt::plane::Ctrl,
    shift: glam::DVec2,
) -> csgrt::plane::Region {
    use csgrt::plane::{Ctrl, Outlines, Region};
    let p = |x: f64, y: f64| glam::DVec2::new(x, y) + shift;
    let outlines = Outlines {
        loops: vec![
            vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 2.0), p(0.0, 2.0)],
            vec![p(0.3, 0.6), p(0.3, 1.4)],
        ],
        ctrl: vec![
            vec![Ctrl::Line, bow(&p), Ctrl::Quad(p(0.5, 2.6)), Ctrl::Line],
            vec![Ctrl::Quad(p(0.9, 1.0)), Ctrl::Quad(p(0.5, 1.0))],
        ],
    };
    Region::new(outlines)
}

/// The curved region with a quadratic bow, moved off the axis and turned
/// about it (quadratic curves only, as a TrueType glyph's).
pub fn curved_lathe() -> csgrt::geometry::Shape {
    use csgrt::plane::Ctrl;
    let region = curved_region(|p| Ctrl::Quad(p(2.2, 1.0)), glam::DVec2::new(0.4, -1.0));
    csgrt::geometry::Shape::Lathe(csgrt::geometry::Lathe::new(std::sync::Arc::new(region)))
}

/// The curved region with a cubic S-bend bow, as a prism whose top section
/// is scaled by `top`.
pub fn curved_prism(top: f64) -> csgrt::geometry::Shape {
    use csgrt::plane::Ctrl;
    let region = curved_region(|p| Ctrl::Cubic(p(2.6, 0.3), p(0.2, 1.3)), glam::DVec2::ZERO);
    csgrt::geometry::Shape::Prism(csgrt::geometry::Prism::new(
        std::sync::Arc::new(region),
        top,
        true,
    ))
}

/// The L of [`l_prism`] offset by `r` (grown or shrunk, round corners) and
/// extruded.
pub fn l_offset(r: f64) -> csgrt::geometry::Shape {
    csgrt::geometry::Shape::OffsetPrism(csgrt::geometry::OffsetPrism {
        region: std::sync::Arc::new(csgrt::plane::round_offset::RoundOffset::new(l_region(), r)),
        centered: false,
    })
}

/// A convex mesh: the octahedron of the unit axis points.
pub fn octahedron() -> Shape {
    use csgrt::geometry::mesh::{Mesh, MeshData};
    let v = [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    let t = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    Shape::Mesh(Mesh {
        data: std::sync::Arc::new(MeshData::new(v.to_vec(), t.to_vec())),
    })
}

/// hull() of two balls (a tapered capsule) and minkowski() of a cube
/// and a ball (a rounded box), within the unit box.
pub fn hull_and_sum() -> [Shape; 2] {
    use csgrt::geometry::convex::{Convex, ConvexPart};
    let ball = |c: DVec3, r: f64| ConvexPart {
        shape: Shape::Sphere(Sphere),
        to_world: DAffine3::from_scale_rotation_translation(DVec3::splat(r), DQuat::IDENTITY, c),
    };
    let cube = ConvexPart {
        shape: Shape::Cuboid(Cuboid { centered: true }),
        to_world: DAffine3::from_scale(DVec3::new(1.2, 0.8, 0.6)),
    };
    [
        Shape::Convex(Convex::new(vec![vec![
            ball(DVec3::new(-0.5, 0.0, 0.0), 0.5),
            ball(DVec3::new(0.8, 0.1, 0.0), 0.2),
        ]])),
        Shape::Convex(Convex::new(vec![vec![cube], vec![ball(DVec3::ZERO, 0.3)]])),
    ]
}

/// minkowski() of a box and a ball written out as exact pieces (a mesh,
/// cylinders and balls: `geometry::ball_sum`), its support from the sum's
/// hulls.
pub fn rounded_box() -> Shape {
    use csgrt::geometry::convex::ConvexPart;
    let half = DVec3::new(0.6, 0.4, 0.3);
    let r = 0.25;
    let mut corners = Vec::new();
    for i in 0..8 {
        let s = |k: usize| if i & (1 << k) == 0 { -1.0 } else { 1.0 };
        corners.push(half * DVec3::new(s(0), s(1), s(2)));
    }
    let pieces = csgrt::geometry::ball_sum::pieces(&corners, r).expect("a box rounds");
    let hulls = vec![
        vec![ConvexPart {
            shape: Shape::Cuboid(Cuboid { centered: true }),
            to_world: DAffine3::from_scale(half),
        }],
        vec![ConvexPart {
            shape: Shape::Sphere(Sphere),
            to_world: DAffine3::from_scale_rotation_translation(
                DVec3::splat(r),
                DQuat::IDENTITY,
                DVec3::ZERO,
            ),
        }],
    ];
    Shape::Rounded(csgrt::geometry::Rounded::new(pieces.parts, hulls).expect("placed"))
}

/// The shadow (`projection(cut = false)`) of the L of [`l_prism`] without
/// its hole, as a soup of triangles, swept from z = 0 to 1.
pub fn l_shadow() -> Shape {
    use csgrt::geometry::shadow::{Shadow, Soup};
    let pts = l_points();
    // Overlapping triangles, as a solid's faces project: the lower bar
    // twice, the upright once.
    let tris = vec![[0, 1, 2], [0, 2, 3], [0, 1, 3], [0, 3, 4], [0, 4, 5]];
    Shape::Shadow(Shadow {
        soup: std::sync::Arc::new(Soup::new(pts, tris).expect("a soup")),
    })
}

/// Whether p is in the figure, read here (even-odd crossings of straight
/// loops, the unit disc's image, the set operations) and not by the
/// kernel's own inside tests.
pub fn figure_contains(f: &csgrt::plane::figure::Figure, p: glam::DVec2) -> bool {
    use csgrt::math::boolean::Op;
    use csgrt::plane::figure::Figure;
    match f {
        Figure::Polygon(o) => {
            assert!(!o.curved(), "a curved outline");
            even_odd(&o.loops, p)
        }
        Figure::Ellipse(e) => e.inverse().transform_point2(p).length_squared() <= 1.0,
        Figure::Op(op, kids) => {
            let mut inside = kids.iter().map(|k| figure_contains(k, p));
            match op {
                Op::Union => inside.any(|x| x),
                Op::Intersection => inside.all(|x| x),
                Op::Difference => inside.next().unwrap_or(false) && !inside.any(|x| x),
                Op::Xor => inside.filter(|&x| x).count() % 2 == 1,
            }
        }
        other => panic!("a figure leaf this reader does not know: {other:?}"),
    }
}

/// Even-odd: p is inside when a ray to +x crosses the loops' edges an odd
/// number of times.
pub fn even_odd(loops: &[Vec<glam::DVec2>], p: glam::DVec2) -> bool {
    let mut odd = false;
    for l in loops {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if x > p.x {
                    odd = !odd;
                }
            }
        }
    }
    odd
}

/// Compares `got` (inside or not) with `want`, a signed distance to the
/// true boundary (negative inside), at 40,000 points spread evenly across
/// `lo..hi` (a Halton sequence: no row or column for a thin error to slip
/// between); points within `margin` of the boundary are skipped. Returns
/// how many points were compared.
pub fn agree_on_grid(
    what: &str,
    lo: glam::DVec2,
    hi: glam::DVec2,
    margin: f64,
    got: impl Fn(glam::DVec2) -> bool,
    want: impl Fn(glam::DVec2) -> f64,
) -> usize {
    fn halton(mut i: u32, base: u32) -> f64 {
        let (mut f, mut r) = (1.0, 0.0);
        while i > 0 {
            f /= base as f64;
            r += f * (i % base) as f64;
            i /= base;
        }
        r
    }
    let mut compared = 0;
    for i in 1..=40_000 {
        let p = lo + (hi - lo) * glam::DVec2::new(halton(i, 2), halton(i, 3));
        let d = want(p);
        if d.abs() <= margin {
            continue;
        }
        compared += 1;
        assert_eq!(
            got(p),
            d < 0.0,
            "{what}: at {p:?}, {} the boundary by {}",
            if d < 0.0 { "inside" } else { "outside" },
            d.abs()
        );
    }
    compared
}

/// The signed distance from p to the box lo..hi (negative inside).
pub fn box_distance(p: glam::DVec2, lo: glam::DVec2, hi: glam::DVec2) -> f64 {
    let c = (lo + hi) * 0.5;
    let h = (hi - lo) * 0.5;
    let q = (p - c).abs() - h;
    q.max(glam::DVec2::ZERO).length() + q.x.max(q.y).min(0.0)
}

/// A figure of one straight loop.
pub fn polygon(pts: &[(f64, f64)]) -> csgrt::plane::figure::Figure {
    csgrt::plane::figure::Figure::Polygon(csgrt::plane::Outlines::polygons(vec![pts
        .iter()
        .map(|&(x, y)| glam::DVec2::new(x, y))
        .collect()]))
}

/// How far off the boundary `p·u − h(u)`, maximised over 3600 directions
/// u, may be for the grids of the hull tests (points and sets within 5 of
/// the origin): the best sampled direction is within π/3600 of the
/// normal, and tilting u by δ changes (p − v)·u by at most |p − v|·δ for
/// the set's farthest point v, so 10·π/3600 ≈ 0.0087.
pub fn support_margin() -> f64 {
    10.0 * std::f64::consts::PI / 3600.0
}

/// The signed distance to the convex hull of a set whose support function
/// is `support` (h(u) = max over the set of x·u), maximising p·u − h(u)
/// over 3600 directions: within [`support_margin`] of the truth.
pub fn support_distance(p: glam::DVec2, support: impl Fn(glam::DVec2) -> f64) -> f64 {
    static DIRS: std::sync::OnceLock<Vec<glam::DVec2>> = std::sync::OnceLock::new();
    let dirs = DIRS.get_or_init(|| {
        (0..3600)
            .map(|k| glam::DVec2::from_angle(k as f64 * std::f64::consts::TAU / 3600.0))
            .collect()
    });
    dirs.iter()
        .map(|&u| p.dot(u) - support(u))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// IEC 61966-2-1's decoding of an sRGB value (as a file gives a colour)
/// to a linear one, written out here from the standard, not taken from the
/// crate.
pub fn srgb_decode(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The 8-bit sRGB value of a linear channel: round(255·encode(v)), from
/// the standard's formula.
pub fn srgb_byte(v: f64) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let e = if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (255.0 * e).round() as u8
}

/// [`srgb_decode`] of each channel of a colour given in bytes.
pub fn srgb_decode_bytes(rgb: u32) -> DVec3 {
    let ch = |s: u32| srgb_decode(((rgb >> s) & 255) as f64 / 255.0);
    DVec3::new(ch(16), ch(8), ch(0))
}

/// A JSON array of three numbers (a `--dump-scene` vector) as a vector.
pub fn json_vec3(x: &serde_json::Value) -> DVec3 {
    let a: Vec<f64> = x
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .collect();
    DVec3::new(a[0], a[1], a[2])
}

/// The seed's pinhole camera (slide 6, docs/LANGUAGE.md) of a
/// `--dump-scene` camera, computed here from its eye, lookat, up, fov and
/// size: `du = normalize(look × up)`, `dv = normalize(look × du)`,
/// `fl = width / (2·tan(fov/2))`, `vp = normalize(look)·fl − ½(width·du +
/// height·dv)`.
pub struct DumpCamera {
    pub eye: DVec3,
    /// `normalize(lookat − eye)`.
    pub look: DVec3,
    pub du: DVec3,
    pub dv: DVec3,
    pub vp: DVec3,
    pub fl: f64,
    pub width: f64,
    pub height: f64,
}

impl DumpCamera {
    pub fn of(cam: &serde_json::Value) -> DumpCamera {
        let (eye, lookat, up) = (
            json_vec3(&cam["eye"]),
            json_vec3(&cam["lookat"]),
            json_vec3(&cam["up"]),
        );
        let (width, height) = (
            cam["width"].as_f64().unwrap(),
            cam["height"].as_f64().unwrap(),
        );
        let look = (lookat - eye).normalize();
        let du = look.cross(up).normalize();
        let dv = look.cross(du).normalize();
        let fl = width / (2.0 * (cam["fov"].as_f64().unwrap() * 0.5).to_radians().tan());
        DumpCamera {
            eye,
            look,
            du,
            dv,
            vp: look * fl - 0.5 * (width * du + height * dv),
            fl,
            width,
            height,
        }
    }

    /// The unit direction of the ray through image point (x, y); pixel
    /// (i, j)'s centre is (i + ½, j + ½).
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        (x * self.du + y * self.dv + self.vp).normalize()
    }

    /// The pixel a world point lands in.
    pub fn project(&self, p: DVec3) -> (u32, u32) {
        let d = p - self.eye;
        let s = self.fl / d.dot(self.look);
        (
            (self.width / 2.0 + s * d.dot(self.du)) as u32,
            (self.height / 2.0 + s * d.dot(self.dv)) as u32,
        )
    }

    /// The camera's right, up and back axes (`du`, `−dv`, `−look`): the
    /// axes csgrt's default lights are given in.
    pub fn axes(&self) -> [DVec3; 3] {
        [self.du, -self.dv, -self.look]
    }
}
