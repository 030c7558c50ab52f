//! The seed's display lists, format by extension, and the defaults a scene
//! gets when it says nothing.

use crate::common;
use crate::common::{csgrt, files, scene};
use glam::DVec3;
use std::path::Path;

fn repo(p: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(p)
        .to_str()
        .unwrap()
        .to_string()
}

#[test]
fn the_slide_as_printed_fails_at_its_short_sphere_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        repo("tests/fixtures/slide32-as-printed.ray"),
        dir.path().join("slide32.ray"),
    )
    .unwrap();
    let r = csgrt(dir.path(), &["slide32.ray", "-q"]);
    assert_eq!(r.status, 2);
    assert_eq!(
        r.stderr,
        "error: expected a number, found the end of the line\n  --> slide32.ray:13:17\n   |\n13 | sphere -3 -1 1.5\n   |                 ^\n"
    );
    assert_eq!(files(dir.path()), ["slide32.ray"]);
}

#[test]
fn the_repaired_display_list_and_its_csg_twin_render_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    for (model, out) in [
        ("models/seed.ray", "ray.png"),
        ("models/seed.csg", "csg.png"),
    ] {
        let r = csgrt(
            dir.path(),
            &[&repo(model), "-o", out, "--size", "200x150", "-q"],
        );
        assert_eq!(r.status, 0, "{model}: {}", r.stderr);
    }
    let a = image::open(dir.path().join("ray.png")).unwrap().to_rgb8();
    let b = image::open(dir.path().join("csg.png")).unwrap().to_rgb8();
    assert_eq!(a.as_raw(), b.as_raw());
    // And the picture is not trivially uniform.
    assert!(a.pixels().any(|p| p != a.get_pixel(0, 0)));
}

#[test]
fn a_surface_may_spread_over_lines_and_lights_take_every_form() {
    let (dir, _) = scene(
        "s.ray",
        "eye 0 0 8\nlookat 0 0 0\nup 0 1 0\nfov 40\nbackground 0 0 0\nlight 0.2 0.2 0.2 ambient\nlight 1 1 1 point 3 3 8\nlight 0.5 0.5 0.5 directional 0 0 -1\nsurface\n1 0 0\n0.5 0.5 0.5 20\n0 0 1.5\nsphere 0 0 0 1\n",
    );
    let r = csgrt(
        dir.path(),
        &["s.ray", "--size", "40x40", "-q", "--dump-scene", "d.json"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = common::stats(dir.path(), "d.json");
    assert_eq!(d["lights"].as_array().unwrap().len(), 3);
    assert_eq!(d["materials"][0]["ns"], 20.0);
    assert_eq!(d["camera"]["up"], serde_json::json!([0.0, 1.0, 0.0]));
}

#[test]
fn an_unknown_extension_is_refused() {
    let (dir, _) = scene("part.stl", "solid x\nendsolid x\n");
    let r = csgrt(dir.path(), &["part.stl"]);
    assert_eq!(r.status, 2);
    assert_eq!(
        r.stderr,
        "error: part.stl: unknown model format; expected a `.csg` scene, a `.ray` display list or a `.scad` program\n"
    );
    assert_eq!(files(dir.path()), ["part.stl"]);
}

#[test]
fn default_lights_give_each_visible_face_of_a_cube_its_own_shade() {
    let (dir, _) = scene("c.csg", "cube(10);\n");
    let r = csgrt(
        dir.path(),
        &[
            "c.csg",
            "--size",
            "200x150",
            "--dump-scene",
            "d.json",
            "-q",
            "-o",
            "c.png",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = common::stats(dir.path(), "d.json");
    let img = image::open(dir.path().join("c.png")).unwrap().to_rgb8();
    // The default view sees the top (+z), front (−y) and right (+x) faces.
    let faces = [
        DVec3::new(5.0, 5.0, 10.0),
        DVec3::new(5.0, 0.0, 5.0),
        DVec3::new(10.0, 5.0, 5.0),
    ];
    let shades: Vec<[u8; 3]> = faces
        .iter()
        .map(|&p| {
            let (x, y) = common::DumpCamera::of(&d["camera"]).project(p);
            img.get_pixel(x, y).0
        })
        .collect();
    let bg = img.get_pixel(0, 0).0;
    for (i, a) in shades.iter().enumerate() {
        assert_ne!(*a, bg, "face {i} is visible");
        for b in &shades[i + 1..] {
            let diff: i32 = (0..3)
                .map(|k| (a[k] as i32 - b[k] as i32).abs())
                .max()
                .unwrap();
            assert!(diff >= 12, "faces read alike: {shades:?}");
        }
    }
    // The box fills the frame sensibly: its corners are inside the image.
    for i in 0..8 {
        let c = DVec3::new(
            (i & 1) as f64 * 10.0,
            ((i >> 1) & 1) as f64 * 10.0,
            ((i >> 2) & 1) as f64 * 10.0,
        );
        let (x, y) = common::DumpCamera::of(&d["camera"]).project(c);
        assert!(x < 200 && y < 150, "corner {c} at {x},{y}");
    }
}

#[test]
fn a_halfspace_is_drawn_but_not_framed() {
    let (dir, _) = scene("h.csg", "cube(2);\nhalfspace(offset = 0);\n");
    let r = csgrt(
        dir.path(),
        &["h.csg", "--size", "80x60", "--dump-scene", "d.json", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = common::stats(dir.path(), "d.json");
    assert_eq!(d["camera"]["lookat"], serde_json::json!([1.0, 1.0, 1.0]));
}
