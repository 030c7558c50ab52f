//! Real OpenSCAD exports render with no edits; nodes csgrt cannot render
//! yet stop the run with a message at their place.
//!
//! `tests/openscad/*.scad` were exported to the `.csg` beside them by
//! OpenSCAD 2021.01 (Debian 12's `openscad` package):
//! `openscad -o X.csg X.scad`. `current_format.csg` follows current
//! OpenSCAD's node text, which Debian does not package.

use crate::common;
use crate::common::{csgrt, srgb_decode, srgb_decode_bytes, stats};
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/openscad")
}

/// Renders a fixture with the default view; returns (mask coverage, dump).
fn render(name: &str) -> (f64, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let model = fixtures().join(name);
    let r = csgrt(
        dir.path(),
        &[
            model.to_str().unwrap(),
            "-o",
            "out.png",
            "--size",
            "160x120",
            "--mask",
            "mask.png",
            "--dump-scene",
            "scene.json",
            "-q",
        ],
    );
    assert_eq!(r.status, 0, "{name}: {}", r.stderr);
    assert_eq!(r.stderr, "", "{name} renders without warnings");
    let mask = image::open(dir.path().join("mask.png")).unwrap().to_luma8();
    let hits = mask.pixels().filter(|p| p.0[0] == 255).count();
    (
        hits as f64 / (160.0 * 120.0),
        stats(dir.path(), "scene.json"),
    )
}

fn primitives(node: &serde_json::Value, out: &mut Vec<String>) {
    if let Some(p) = node["primitive"].as_str() {
        out.push(p.to_string());
    }
    if let Some(ch) = node["children"].as_array() {
        for c in ch {
            primitives(c, out);
        }
    }
}

fn prims_of(dump: &serde_json::Value) -> Vec<String> {
    let mut v = Vec::new();
    primitives(&dump["root"], &mut v);
    v
}

#[test]
fn every_exported_fixture_renders_and_fills_a_sensible_share_of_the_view() {
    let expected = [
        ("primitives.csg", 8),
        ("transforms.csg", 9),
        ("booleans.csg", 1 + 15 + 2 + 2 + 4),
        ("colors.csg", 7),
        ("modifiers.csg", 4),
        ("root.csg", 1),
        ("numbers.csg", 4),
        ("current_format.csg", 4),
    ];
    for (name, count) in expected {
        let (coverage, dump) = render(name);
        assert_eq!(prims_of(&dump).len(), count, "{name}: primitives");
        assert!(
            (0.04..0.85).contains(&coverage),
            "{name}: the solid covers {:.1} % of the default view",
            coverage * 100.0
        );
    }
}

#[test]
fn background_and_disabled_subtrees_are_left_out_and_root_wins() {
    let (_, dump) = render("modifiers.csg");
    assert_eq!(prims_of(&dump), ["cube", "sphere", "cube", "sphere"]);
    let (_, dump) = render("root.csg");
    assert_eq!(prims_of(&dump), ["sphere"]);
}

#[test]
fn colours_become_materials_and_no_colour_inherits() {
    let (_, dump) = render("colors.csg");
    let colors: Vec<serde_json::Value> = dump["materials"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["color"].clone())
        .collect();
    // The dump gives the linear values, decoded from the file's sRGB.
    let near = |want: glam::DVec3| {
        colors
            .iter()
            .any(|c| (0..3).all(|k| (c[k].as_f64().unwrap() - want[k]).abs() < 1e-12))
    };
    assert!(near(glam::DVec3::X), "{colors:?}");
    // color("nosuchcolour") was exported as [-1, -1, -1, 1]: the default.
    assert!(near(srgb_decode_bytes(0xf9d72c)), "{colors:?}");
    // color("green", 0.5) transmits half the light.
    let green = dump["materials"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| {
            // OpenSCAD's "green" is #008000, linear 0.2159.
            (m["color"][1].as_f64().unwrap() - srgb_decode(128.0 / 255.0)).abs() < 1e-5
                && m["color"][0] == 0.0
                && m["color"][2] == 0.0
        })
        .expect("a green material");
    assert_eq!(green["kt"], 0.5);
}

#[test]
fn a_statement_newer_than_openscad_2021_is_left_out_with_its_warning() {
    // OpenSCAD 2021.01 answers `roof` and `fill` (later versions'
    // statements), in a solid's place or a 2-D shape's, with "WARNING:
    // Ignoring unknown module 'roof'" and renders the rest: csgrt says
    // the same at each place and renders the picture of the file without
    // them; under --strict it stops at the first and writes nothing.
    let listed: Vec<&str> = csgrt::scene::later_statements().collect();
    assert_eq!(listed, ["roof", "fill"]);
    for node in listed {
        let text = format!(
            "group() {{\n\tcube(1);\n\tlinear_extrude(height = 10) {node}() square(1);\n\t{node}() square(2);\n}}\n"
        );
        let strict = common::lenient(&text, "group() {\n\tcube(1);\n}\n");
        let first = format!("error: Ignoring unknown module '{node}'\n --> bad.csg:3:30\n");
        assert!(strict.starts_with(&first), "{node}: {strict}");
        let (dir, _) = common::scene("bad.csg", &text);
        let r = csgrt(dir.path(), &["bad.csg", "--size", "8x6", "-q"]);
        for (line, col) in [(3, 30), (4, 2)] {
            let at =
                format!("warning: Ignoring unknown module '{node}'\n --> bad.csg:{line}:{col}\n");
            assert!(r.stderr.contains(&at), "{node}: {}", r.stderr);
        }
    }
}

#[test]
fn the_shadow_of_a_difference_with_a_turn_is_cut_into_wedges_with_a_note() {
    // OpenSCAD's own export writes `cut = false` for a plain projection().
    // A turn in a difference is cut into wedges of convex polytopes, the
    // shadow said once as approximated; the shadow of the turned square
    // less the cube's corner is the ring 3 ≤ ρ ≤ 4 without its quarter
    // x, y ∈ [0, 3]: rays down through (3.5, 0.2) (in the cube's shadow)
    // and (−3.5, 0.2) (in the ring) miss and hit.
    let text = "linear_extrude(height = 1) {\n\tprojection(cut = false, convexity = 0) {\n\t\tdifference() { rotate_extrude() translate([3, 0]) square(1); translate([0, 0, -1]) cube(3); }\n\t}\n}\n";
    let (dir, _) = common::scene("s.csg", text);
    std::fs::write(
        dir.path().join("rays"),
        "2.5 0.2 5 0 0 -1\n-3.5 0.2 5 0 0 -1\n",
    )
    .unwrap();
    let r = common::csgrt(dir.path(), &["s.csg", "--trace-rays", "rays"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines[0], "miss", "{}", r.stdout);
    assert!(lines[1].starts_with("4 "), "{}", r.stdout);
    let r = common::csgrt(dir.path(), &["s.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(
        r.stderr.starts_with("note: `projection` of a 3-D difference is approximated by convex polytopes\n --> s.csg:2:2\n"),
        "{}",
        r.stderr
    );
}

#[test]
fn a_resize_without_an_exact_extent_measures_convex_polytopes() {
    // A cube cut by a ball at a corner: Csg::extreme cannot show the
    // extent of what is left (the ball cuts the side it looks at), so the
    // difference is cut into polytopes, whose extent along x is the cube's
    // own: resize to 2 is scale 2, to the byte.
    let cut = "difference() {\n\t\tcube(1);\n\t\tsphere(r = 0.5);\n\t}";
    let (dir, _) = common::scene(
        "r.csg",
        &format!("resize(newsize = [2, 0, 0]) {{\n\t{cut}\n}}\n"),
    );
    std::fs::write(
        dir.path().join("s.csg"),
        format!("scale([2, 1, 1]) {{\n\t{cut}\n}}\n"),
    )
    .unwrap();
    let r = common::csgrt(dir.path(), &["r.csg", "s.csg", "--size", "40x30", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(
        r.stderr
            .contains("note: `resize` of a 3-D difference is approximated"),
        "{}",
        r.stderr
    );
    let read = |f: &str| std::fs::read(dir.path().join(f)).unwrap();
    assert!(read("r.png") == read("s.png"));
}
