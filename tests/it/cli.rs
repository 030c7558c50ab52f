//! The command line: outputs, counters, determinism and whole error messages.

use crate::common;
use crate::common::{csgrt, csgrt_stdin, fails, files, scene, srgb_byte, srgb_decode, stats};

const SPHERE: &str = "camera(eye = [0, -6, 0], lookat = [0, 0, 0]);\nsphere(1);\n";

#[test]
fn renders_a_png_beside_the_model_by_default() {
    let (dir, _) = scene("ball.csg", SPHERE);
    let r = csgrt(dir.path(), &["ball.csg", "--size", "40x30", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(r.stderr, "");
    let img = image::open(dir.path().join("ball.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (40, 30));
    // The centre shows the sphere, a corner the background.
    assert_ne!(img.get_pixel(20, 15), img.get_pixel(0, 0));
}

#[test]
fn a_mask_marks_exactly_the_pixels_whose_centre_ray_hits() {
    let (dir, _) = scene("ball.csg", SPHERE);
    let r = csgrt(
        dir.path(),
        &["ball.csg", "--size", "64x64", "--mask", "m.png", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let m = image::open(dir.path().join("m.png")).unwrap().to_luma8();
    // Camera at distance 6, fov 30°: the sphere's angular radius is
    // asin(1/6); a pixel centre hits iff its ray is within that angle.
    let fl = 64.0 / (2.0 * (15f64).to_radians().tan());
    let mut hits = 0;
    for (x, y, p) in m.enumerate_pixels() {
        let (dx, dy) = (x as f64 + 0.5 - 32.0, y as f64 + 0.5 - 32.0);
        let angle = ((dx * dx + dy * dy).sqrt() / fl).atan();
        let want = angle < (1.0f64 / 6.0).asin();
        assert_eq!(p.0[0] == 255, want, "pixel {x},{y}");
        assert!(p.0[0] == 0 || p.0[0] == 255);
        hits += want as u32;
    }
    assert!(hits > 100);
}

#[test]
fn counters_show_no_secondary_rays_without_kr_or_kt() {
    let (dir, _) = scene(
        "s.csg",
        "camera(eye = [0, -6, 2], lookat = [0, 0, 0]);\ndirectional_light([1, 1, 1], [0, 1, -1]);\nmaterial(kr = 0, kt = 0) { sphere(1); cube(3, center = true); }\n",
    );
    let start = std::time::Instant::now();
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "32x24", "--stats-json", "st.json", "-q"],
    );
    let wall = start.elapsed().as_secs_f64();
    assert_eq!(r.status, 0, "{}", r.stderr);
    let s = stats(dir.path(), "st.json");
    assert_eq!(s["pixels"], 32 * 24);
    // One sample a pixel: a ray cast, or the background where the
    // scene's box is not seen.
    assert_eq!(
        s["primary_rays"].as_u64().unwrap() + s["screen_culled"].as_u64().unwrap(),
        32 * 24
    );
    assert_eq!(s["reflected_rays"], 0);
    assert_eq!(s["refracted_rays"], 0);
    assert!(s["shadow_rays"].as_u64().unwrap() > 0);
    assert!(s["primitive_tests"].as_u64().unwrap() > 0);
    // The render is timed, and within the whole process's run.
    let render = s["render_seconds"].as_f64().unwrap();
    assert!(render > 0.0 && render < wall, "{render} s of {wall} s");
    for key in ["bound_tests", "bound_culled", "normals_computed"] {
        assert!(s[key].is_u64(), "{key}");
    }
}

#[test]
fn counters_count_reflected_and_refracted_rays_when_asked_for() {
    let (dir, _) = scene(
        "s.csg",
        "camera(eye = [0, -6, 0], lookat = [0, 0, 0]);\nmaterial(kr = 0.5, kt = 0.5) sphere(1);\n",
    );
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "32x24", "--stats-json", "st.json", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let s = stats(dir.path(), "st.json");
    assert!(s["reflected_rays"].as_u64().unwrap() > 0);
    assert!(s["refracted_rays"].as_u64().unwrap() > 0);
}

#[test]
fn only_ambient_light_casts_no_shadow_rays() {
    let (dir, _) = scene(
        "s.csg",
        "camera(eye = [0, -6, 0], lookat = [0, 0, 0]);\nambient_light([1, 1, 1]);\nsphere(1);\n",
    );
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "32x24", "--stats-json", "st.json", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let s = stats(dir.path(), "st.json");
    assert_eq!(s["shadow_rays"], 0);
    assert!(s["normals_computed"].as_u64().unwrap() > 0);
}

#[test]
fn the_image_is_identical_for_any_thread_count() {
    let (dir, _) = scene(
        "s.csg",
        "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\nmaterial(kr = 0.3) difference() { cube(2, center = true); sphere(1.3); }\nmaterial(kt = 0.6) translate([0, -2, 0]) sphere(0.5);\n",
    );
    for (t, out) in [("1", "a.png"), ("3", "b.png"), ("2", "c.png")] {
        let r = csgrt(
            dir.path(),
            &[
                "s.csg",
                "--size",
                "48x36",
                "--spp",
                "5",
                "--threads",
                t,
                "-o",
                out,
                "-q",
            ],
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
    }
    let a = std::fs::read(dir.path().join("a.png")).unwrap();
    assert_eq!(a, std::fs::read(dir.path().join("b.png")).unwrap());
    assert_eq!(a, std::fs::read(dir.path().join("c.png")).unwrap());
}

#[test]
fn trace_rays_prints_distance_and_outward_normal_or_miss() {
    let (dir, _) = scene("s.csg", "sphere(1);\n");
    let r = csgrt_stdin(
        dir.path(),
        &["s.csg", "--trace-rays", "-"],
        Some("0 0 -5 0 0 1\n# a comment\n\n0 0 0 0 0 2\n5 5 5 1 0 0\n"),
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(r.stdout, "4 0 0 -1\n1 0 0 1\nmiss\n");
    assert_eq!(files(dir.path()), ["s.csg"]);
}

#[test]
fn a_bad_ray_line_is_an_error_with_its_place_and_no_output() {
    let (dir, _) = scene("s.csg", "sphere(1);\n");
    let r = csgrt_stdin(
        dir.path(),
        &["s.csg", "--trace-rays", "-"],
        Some("0 0 -5 0 0 1\n0 0 x 0 0 1\n"),
    );
    assert_eq!(r.status, 2);
    assert_eq!(r.stdout, "");
    assert_eq!(
        r.stderr,
        "error: `x` is not a finite number\n --> <stdin>:2:5\n  |\n2 | 0 0 x 0 0 1\n  |     ^ expected `ox oy oz dx dy dz`\n"
    );
}

#[test]
fn dump_scene_gives_camera_lights_materials_and_world_matrices() {
    let (dir, _) = scene(
        "s.csg",
        "translate([1, 2, 3]) color([1, 0, 0]) sphere(2);\n",
    );
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "8x6", "--dump-scene", "d.json", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = stats(dir.path(), "d.json");
    assert_eq!(d["camera"]["width"], 8);
    assert_eq!(d["root"]["primitive"], "sphere");
    assert_eq!(
        d["root"]["matrix"],
        serde_json::json!([
            [2.0, 0.0, 0.0, 1.0],
            [0.0, 2.0, 0.0, 2.0],
            [0.0, 0.0, 2.0, 3.0],
            [0.0, 0.0, 0.0, 1.0]
        ])
    );
    assert_eq!(
        d["materials"][0]["color"],
        serde_json::json!([1.0, 0.0, 0.0])
    );
    // No lights in the file: the default rig about the camera, its key
    // light the only one with shadows.
    let lights = d["lights"].as_array().unwrap();
    let shadows: Vec<_> = lights.iter().map(|l| l["shadows"].as_bool()).collect();
    assert_eq!(shadows, [None, Some(true), Some(false), Some(false)]);
    let [right, up, back] = common::DumpCamera::of(&d["camera"]).axes();
    // The key comes from the upper left in front of the camera, as
    // docs/LANGUAGE.md says: (-0.5, 0.5, 0.7) in (right, up, back).
    let towards = -common::json_vec3(&lights[1]["direction"]);
    let want = glam::DVec3::new(-0.5, 0.5, 0.7).normalize();
    let got = glam::DVec3::new(towards.dot(right), towards.dot(up), towards.dot(back));
    assert!((got - want).length() < 1e-12, "{got} vs {want}");
}

#[test]
fn an_unknown_argument_lists_the_known_ones() {
    assert_eq!(
        fails("union() {\n  cube(sise = 2);\n}\n"),
        "error: unknown argument `sise` for `cube`\n --> bad.csg:2:8\n  |\n2 |   cube(sise = 2);\n  |        ^^^^ expected `size` or `center`\n"
    );
}

#[test]
fn an_unknown_statement_is_named() {
    assert_eq!(
        fails("sphere(1);\nspehre(2);\n"),
        "error: unknown statement `spehre`\n --> bad.csg:2:1\n  |\n2 | spehre(2);\n  | ^^^^^^ expected a solid, a transform, a CSG operation, color, material or a scene statement\n"
    );
}

#[test]
fn a_syntax_error_says_what_was_expected() {
    assert_eq!(
        fails("translate([1, 2 3]) cube();\n"),
        "error: expected `,` or `]`, found `3`\n --> bad.csg:1:17\n  |\n1 | translate([1, 2 3]) cube();\n  |                 ^\n"
    );
}

#[test]
fn a_value_of_the_wrong_type_is_pointed_at() {
    assert_eq!(
        fails("sphere(r = \"big\");\n"),
        "error: `r` of `sphere` must be a number\n --> bad.csg:1:12\n  |\n1 | sphere(r = \"big\");\n  |            ^^^^^ expected a number, found a string\n"
    );
}

#[test]
fn a_light_without_a_direction_is_an_error() {
    assert_eq!(
        fails("directional_light([1, 1, 1]);\nsphere();\n"),
        "error: `directional_light` needs the argument `direction`\n --> bad.csg:1:18\n  |\n1 | directional_light([1, 1, 1]);\n  |                  ^^^^^^^^^^^ expected `direction = …`\n"
    );
}

#[test]
fn a_degenerate_camera_is_an_error() {
    assert_eq!(
        fails("camera(eye = [0, 0, 5], lookat = [0, 0, 0]);\nsphere();\n"),
        "error: the camera's `up` is parallel to its view direction\n --> bad.csg:1:7\n  |\n1 | camera(eye = [0, 0, 5], lookat = [0, 0, 0]);\n  |       ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^ expected an `up` that is not along `lookat - eye`\n"
    );
}

#[test]
fn a_bad_size_is_a_usage_error() {
    let (dir, _) = scene("s.csg", SPHERE);
    let r = csgrt(dir.path(), &["s.csg", "--size", "800by600"]);
    assert_eq!(r.status, 2);
    assert!(
        r.stderr.contains("invalid value '800by600' for '--size <WxH>': `800by600` is not a size: expected WxH, as in 800x600"),
        "{}",
        r.stderr
    );
    assert_eq!(files(dir.path()), ["s.csg"]);
}

#[test]
fn the_output_may_not_be_the_model() {
    let (dir, _) = scene("s.csg", SPHERE);
    let r = csgrt(dir.path(), &["s.csg", "-o", "s.csg", "-q"]);
    assert_eq!(r.status, 2);
    assert_eq!(
        r.stderr,
        "error: s.csg: an output may not overwrite the model\n"
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("s.csg")).unwrap(),
        SPHERE
    );
}

#[test]
fn a_missing_font_family_falls_back_to_the_built_in_font_with_a_warning() {
    let text = "linear_extrude(1) text(\"Hi\", font = \"Nowhere Sans:style=Bold\");\n";
    let (dir, _) = scene("f.csg", text);
    let r = csgrt(dir.path(), &["f.csg", "--size", "40x30", "-q"]);
    assert_eq!(r.status, 0);
    assert_eq!(
        r.stderr,
        "warning: font `Nowhere Sans` is not installed; using Liberation Sans:style=Bold\n --> f.csg:1:37\n  |\n1 | linear_extrude(1) text(\"Hi\", font = \"Nowhere Sans:style=Bold\");\n  |                                     ^^^^^^^^^^^^^^^^^^^^^^^^^ expected an installed family (Liberation Sans is built in)\n"
    );
    // The same picture as the built-in family named outright.
    let (dir2, _) = scene("f.csg", &text.replace("Nowhere Sans", "Liberation Sans"));
    let r2 = csgrt(dir2.path(), &["f.csg", "--size", "40x30", "-q"]);
    assert_eq!((r2.status, r2.stderr.as_str()), (0, ""));
    let a = std::fs::read(dir.path().join("f.png")).unwrap();
    let b = std::fs::read(dir2.path().join("f.png")).unwrap();
    assert_eq!(a, b);
}

#[test]
fn a_drawing_that_is_no_dxf_is_a_warning_at_its_file() {
    let (dir, _) = scene("d.csg", "linear_extrude(1) import(\"junk.dxf\");\n");
    std::fs::write(
        dir.path().join("junk.dxf"),
        "  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n 10\nnot a number\n",
    )
    .unwrap();
    let r = csgrt(dir.path(), &["d.csg", "--size", "8x6", "-q", "--strict"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(
        r.stderr
            .starts_with("error: `junk.dxf` is not a DXF drawing csgrt can read: "),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains(" --> d.csg:1:26\n"), "{}", r.stderr);
    assert_eq!(files(dir.path()), ["d.csg", "junk.dxf"]);
}

#[test]
fn a_bad_svg_drawing_is_an_error_at_its_file_naming_its_line() {
    let (dir, _) = scene("d.csg", "linear_extrude(1) import(\"bad.svg\");\n");
    std::fs::write(
        dir.path().join("bad.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\">\n  <rect width=\"1\" height=\"1\"/>\n  <path d=\"M 0 0 L 1 x\"/>\n</svg>\n",
    )
    .unwrap();
    let r = csgrt(dir.path(), &["d.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(
        r.stderr
            .starts_with("error: `bad.svg`, line 3: `path` data: "),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains(" --> d.csg:1:26\n"), "{}", r.stderr);
    assert!(
        r.stderr.contains("expected an SVG drawing csgrt can read"),
        "{}",
        r.stderr
    );
    assert_eq!(files(dir.path()), ["bad.svg", "d.csg"]);
    // A curved open path is stroked along libsvg's points of it, as
    // OpenSCAD strokes it (OpenSCAD's own suite checks the picture).
    std::fs::write(
        dir.path().join("bad.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M 0 0 Q 5 5 10 0\"/></svg>",
    )
    .unwrap();
    let r = csgrt(
        dir.path(),
        &["d.csg", "--size", "8x6", "-q", "-o", "stroke.png"],
    );
    assert_eq!((r.status, r.stderr.as_str()), (0, ""));
    std::fs::remove_file(dir.path().join("stroke.png")).unwrap();
    // Cubic curves offset: flattened to straight polygons, noted at the
    // offset.
    std::fs::write(
        dir.path().join("bad.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M 0 0 C 5 5 10 5 10 0 Z\"/></svg>",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("d.csg"),
        "linear_extrude(1) offset(r = 1) import(\"bad.svg\");\n",
    )
    .unwrap();
    let r = csgrt(dir.path(), &["d.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(
        r.stderr.starts_with(
            "note: an `offset` of curves, ellipses, hulls or projections is approximated by straight polygons\n --> d.csg:1:19\n"
        ),
        "{}",
        r.stderr
    );
    std::fs::remove_file(dir.path().join("d.png")).unwrap();
    std::fs::write(
        dir.path().join("d.csg"),
        "linear_extrude(1) import(\"bad.svg\");\n",
    )
    .unwrap();
    // A missing one: the system's reason.
    std::fs::remove_file(dir.path().join("bad.svg")).unwrap();
    let r = csgrt(dir.path(), &["d.csg", "--size", "8x6", "-q", "--strict"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(
        r.stderr
            .starts_with("error: cannot read drawing `bad.svg`: "),
        "{}",
        r.stderr
    );
}

#[test]
fn svg_text_and_images_are_left_out_with_a_warning() {
    let (dir, _) = scene("d.csg", "linear_extrude(1) import(\"t.svg\");\n");
    std::fs::write(
        dir.path().join("t.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"4\" height=\"2\"/><text>hi</text><text>ho</text><image href=\"x.png\"/></svg>",
    )
    .unwrap();
    let r = csgrt(dir.path(), &["d.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(
        r.stderr
            .starts_with("warning: elements of the drawing left out: 2 `text`, 1 `image`\n"),
        "{}",
        r.stderr
    );
}

#[test]
fn an_empty_scene_warns_and_renders_the_background() {
    let (dir, _) = scene("e.csg", "background([0, 0, 1]);\n");
    let r = csgrt(dir.path(), &["e.csg", "--size", "4x3", "-q"]);
    assert_eq!(r.status, 0);
    assert_eq!(
        r.stderr,
        "warning: the scene has no solids\n --> e.csg:1:1\n  |\n1 | background([0, 0, 1]);\n  | ^^^^^^^^^^^^^^^^^^^^^^ only the background will show\n"
    );
    let img = image::open(dir.path().join("e.png")).unwrap().to_rgb8();
    assert!(img.pixels().all(|p| p.0 == [0, 0, 255]));
}

#[test]
fn root_modifier_renders_only_its_subtree_without_its_parents_transform() {
    let (dir, _) = scene(
        "r.csg",
        "cube(10);\ntranslate([15, 0, 0]) !sphere(5);\n%cylinder(h = 3);\n",
    );
    let r = csgrt(
        dir.path(),
        &["r.csg", "--size", "8x6", "--dump-scene", "d.json", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = stats(dir.path(), "d.json");
    assert_eq!(d["root"]["primitive"], "sphere");
    assert_eq!(d["root"]["matrix"][0][3], 0.0);
}

#[test]
fn disabled_and_background_statements_are_left_out() {
    let (dir, _) = scene("m.csg", "#cube(1);\n%sphere(5);\n*cylinder(h = 3);\n");
    let r = csgrt(
        dir.path(),
        &["m.csg", "--size", "8x6", "--dump-scene", "d.json", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = stats(dir.path(), "d.json");
    assert_eq!(d["root"]["primitive"], "cube");
}

#[test]
fn export_pov_writes_one_complete_file() {
    // What the SDL says is checked against the model by an independent
    // reader of both (tools/oracle/pov_check.py, in .ci/run); here only the
    // command's contract: status 0, the export beside the model,
    // a whole one (and no image: an export alone renders nothing).
    let (dir, _) = scene(
        "p.csg",
        &std::fs::read_to_string("tests/scenes/export.csg").unwrap(),
    );
    let r = csgrt(
        dir.path(),
        &["p.csg", "--size", "40x30", "--export-pov", "p.pov", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let sdl = std::fs::read_to_string(dir.path().join("p.pov")).unwrap();
    let opens = sdl.matches('{').count();
    assert!(opens > 0 && opens == sdl.matches('}').count(), "{sdl}");
    assert_eq!(files(dir.path()), ["p.csg", "p.pov"]);
}

/// The image and the warnings of `text` (with a camera that sees the
/// origin's neighbourhood, 64×48, one sample).
fn image_of(text: &str) -> (Vec<u8>, String) {
    let (dir, _) = scene(
        "p.csg",
        &format!("camera(eye = [8, -12, 10], lookat = [1, 1, 0], fov = 40);\n{text}"),
    );
    let r = csgrt(
        dir.path(),
        &["p.csg", "--size", "64x48", "--spp", "1", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let img = image::open(dir.path().join("p.png")).unwrap().to_rgb8();
    (img.into_raw(), r.stderr)
}

#[test]
fn polygons_openscad_leaves_out_are_left_out_with_a_warning_at_their_place() {
    // OpenSCAD 2021.01 renders the rest of a model around a polygon it
    // cannot read (no points, a point that is not 2 numbers, fewer than 3
    // points: nothing; an index out of range: dropped from its path), so
    // csgrt does too. The picture is the picture without them.
    let cube = "translate([2, 0, 0]) cube(1);\n";
    let (alone, quiet) = image_of(cube);
    assert_eq!(quiet, "");
    let bad = [
        (
            "linear_extrude(1) polygon(points = undef, paths = undef, convexity = 1);\n",
            "warning: this `polygon` is empty\n --> p.csg:2:26\n  |\n2 | linear_extrude(1) polygon(points = undef, paths = undef, convexity = 1);\n  |                          ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^ it has no `points` (as in OpenSCAD, it is left out)\n",
        ),
        (
            "linear_extrude(1) polygon(points = [[0, 0], [1, 0], undef]);\n",
            "warning: `points` of `polygon` must be a point of 2 numbers; the polygon is left out, as in OpenSCAD\n --> p.csg:2:53\n  |\n2 | linear_extrude(1) polygon(points = [[0, 0], [1, 0], undef]);\n  |                                                     ^^^^^ expected a point of 2 numbers, found `undef`\n",
        ),
        (
            "linear_extrude(1) polygon(points = [[0, 0], [1, 0]]);\n",
            "warning: a polygon needs at least 3 points\n --> p.csg:2:36\n  |\n2 | linear_extrude(1) polygon(points = [[0, 0], [1, 0]]);\n  |                                    ^^^^^^^^^^^^^^^^ expected 3 or more points, found 2\n",
        ),
        (
            "linear_extrude(1) polygon(points = [[0, 0], [1, 0], [0, 1]], paths = [[0, 1]]);\n",
            "warning: a path of fewer than 3 points adds nothing\n --> p.csg:2:71\n  |\n2 | linear_extrude(1) polygon(points = [[0, 0], [1, 0], [0, 1]], paths = [[0, 1]]);\n  |                                                                       ^^^^^^ expected 3 or more points, found 2\n",
        ),
        (
            "polyhedron(points = [], faces = undef, convexity = 1);\n",
            "warning: this `polyhedron` is empty\n --> p.csg:2:11\n  |\n2 | polyhedron(points = [], faces = undef, convexity = 1);\n  |           ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^ it has no points or no faces (as in OpenSCAD, it is left out)\n",
        ),
    ];
    for (line, warning) in bad {
        let (img, said) = image_of(&format!("{line}{cube}"));
        assert_eq!(said, warning);
        assert!(img == alone, "{line} changed the picture");
    }
    // An index out of range leaves the rest of its path: the triangle of
    // the other three.
    let (triangle, _) = image_of(&format!(
        "linear_extrude(1) polygon(points = [[0, 0], [1, 0], [0, 1]], paths = [[0, 1, 2]]);\n{cube}"
    ));
    assert!(triangle != alone);
    let (img, said) = image_of(&format!(
        "linear_extrude(1) polygon(points = [[0, 0], [1, 0], [0, 1]], paths = [[0, 1, 3, 2]]);\n{cube}"
    ));
    assert_eq!(said, "warning: index 3 in `paths` of `polygon` is out of range; it is dropped from its path, as in OpenSCAD\n --> p.csg:2:78\n  |\n2 | linear_extrude(1) polygon(points = [[0, 0], [1, 0], [0, 1]], paths = [[0, 1, 3, 2]]);\n  |                                                                              ^ expected a whole number from 0 to 2\n");
    assert!(img == triangle);
}

#[test]
fn a_child_of_the_other_dimension_is_left_out_as_openscad_renders_it() {
    // OpenSCAD 2021.01's render (GeometryEvaluator::applyToChildren): an
    // operation has the dimension of its first child; a child of the other
    // dimension is empty there, with a warning; an empty operand empties a
    // 2-D minkowski (Clipper's sum with no paths). The picture is the
    // picture of what is left.
    let cube = "translate([2, 0, 0]) cube(1);\n";
    let square = "linear_extrude(1) square(1);\n";
    let (alone, _) = image_of(cube);
    let (with_square, _) = image_of(&format!("{cube}{square}"));
    let cases = [
        // An extrusion of a 3-D child extrudes nothing.
        (
            format!("linear_extrude(height = 2) {{\n  cube(1);\n}}\n{cube}"),
            &alone,
            "Ignoring 3D child object for 2D operation",
        ),
        // A 2-D difference is not cut by a solid.
        (
            format!("{cube}linear_extrude(1) difference() {{ square(1); sphere(0.5); }}\n"),
            &with_square,
            "Ignoring 3D child object for 2D operation",
        ),
        // A 3-D union (its first child a solid) leaves a 2-D child out.
        (
            format!("union() {{ {}  square(3); }}\n", cube),
            &alone,
            "Ignoring 2D child object for 3D operation",
        ),
        // A 3-D intersection with a 2-D child is empty.
        (
            format!("{cube}intersection() {{ cube(5); square(3); }}\n"),
            &alone,
            "Ignoring 2D child object for 3D operation",
        ),
        // A 2-D minkowski with an empty operand is empty.
        (
            format!("{cube}linear_extrude(1) minkowski() {{ square(1); circle(r = 0); }}\n"),
            &alone,
            "this `circle` is empty",
        ),
    ];
    for (text, want, says) in cases {
        let (img, said) = image_of(&text);
        assert!(said.contains(says), "{text}: {said}");
        assert!(&img == want, "{text}: another picture");
    }
    assert!(alone != with_square);
}

#[test]
fn bad_2d_shapes_and_extrusions_are_errors_at_their_place() {
    // (A polygon that crosses itself, offset, renders: OpenSCAD reads it
    // by parity first, as csgrt does — tests/openscad/offset_self_touching
    // against OpenSCAD's own mesh.)
    // A drawing that is not there, or a format no one imports: OpenSCAD
    // warns and renders the rest, so csgrt does, the warning at the file
    // argument.
    let rest = "translate([3, 0, 0]) cube();\n";
    // (an import of an SVG drawing is 2-D even when empty: as OpenSCAD, a
    // solid beside it would be left out.)
    let flat = "translate([3, 0]) square();\n";
    assert_eq!(
        common::lenient(&format!("linear_extrude(1) import(file = \"nope.dxf\");\n{rest}"), rest),
        "error: cannot read drawing `nope.dxf`: No such file or directory (os error 2)\n --> bad.csg:1:33\n  |\n1 | linear_extrude(1) import(file = \"nope.dxf\");\n  |                                 ^^^^^^^^^^ expected a DXF file beside the scene; this `import` is left out, as OpenSCAD leaves it out (an error under --strict)\n"
    );
    assert_eq!(
        common::lenient(&format!("import(\"part.svg\");\n{flat}"), flat),
        "error: cannot read drawing `part.svg`: No such file or directory (os error 2)\n --> bad.csg:1:8\n  |\n1 | import(\"part.svg\");\n  |        ^^^^^^^^^^ expected an SVG file beside the scene; this `import` is left out, as OpenSCAD leaves it out (an error under --strict)\n"
    );
    assert_eq!(
        common::lenient(&format!("import(\"part.eps\");\n{flat}"), flat),
        "error: cannot import `part.eps`: not a drawing or mesh file\n --> bad.csg:1:8\n  |\n1 | import(\"part.eps\");\n  |        ^^^^^^^^^^ csgrt imports DXF and SVG drawings and STL, OFF, OBJ, 3MF, AMF and NEF3 meshes; this `import` is left out, as OpenSCAD leaves it out (an error under --strict)\n"
    );
    // A text that is no string, at the value.
    assert_eq!(
        fails("text(text = 5);\n"),
        "error: `text` of `text` must be a string\n --> bad.csg:1:13\n  |\n1 | text(text = 5);\n  |             ^ expected a string, found a number\n"
    );
}

#[test]
fn polyhedron_indices_out_of_range_are_dropped_with_a_warning_as_in_openscad() {
    // OpenSCAD 2021.01 warns "Point index 7 is out of bounds (from
    // faces[4][2])", drops it from its face, and a face left with fewer
    // than 3 points adds nothing: the picture is the tetrahedron's.
    let tet = "polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]";
    let (alone, quiet) = image_of(&format!("{tet}]);\n"));
    assert_eq!(quiet, "");
    let (img, said) = image_of(&format!("{tet}, [0, 1, 7]]);\n"));
    assert!(img == alone);
    assert!(
        said.starts_with("warning: index 7 in `faces` of `polyhedron` is out of range; it is dropped from its face, as in OpenSCAD\n --> p.csg:2:"),
        "{said}"
    );
    assert!(
        said.contains("warning: a face of fewer than 3 points adds nothing"),
        "{said}"
    );
}

#[test]
fn a_shape_across_the_axis_is_not_turned_as_in_openscad() {
    // OpenSCAD 2021.01 reports its error, with the range, and renders the
    // rest of the model: csgrt warns at the place and leaves it out.
    let cube = "translate([2, 0, 0]) cube(1);\n";
    let (alone, _) = image_of(cube);
    let (img, said) = image_of(&format!(
        "rotate_extrude() translate([-1, 0]) square(3);\n{cube}"
    ));
    assert_eq!(
        said,
        "warning: all points for rotate_extrude() must have the same X coordinate sign (range is -1.00 -> 2.00); it is left out, as in OpenSCAD\n --> p.csg:2:1\n  |\n2 | rotate_extrude() translate([-1, 0]) square(3);\n  | ^^^^^^^^^^^^^^ expected a 2-D shape on one side of the axis x = 0\n"
    );
    assert!(img == alone);
}

#[test]
fn an_unknown_facets_mode_is_a_usage_error() {
    let (dir, _) = scene("s.csg", SPHERE);
    let r = csgrt(dir.path(), &["s.csg", "--facets", "smooth"]);
    assert_eq!(r.status, 2);
    assert!(
        r.stderr
            .contains("`smooth` is not a facets mode: expected shapes, exact or openscad"),
        "{}",
        r.stderr
    );
    assert_eq!(files(dir.path()), ["s.csg"]);
    // What it does not facet is drawn exact, with a warning at its place:
    // the picture `--facets exact` draws; under --strict, an error.
    let (dir, _) = scene(
        "t.csg",
        "linear_extrude(height = 2, twist = 30) union() { square(1); translate([2, 0]) square(1); }\n",
    );
    let run = |args: &[&str]| {
        let mut v = vec!["t.csg", "--size", "16x12"];
        v.extend(args);
        csgrt(dir.path(), &v)
    };
    let r = run(&["--facets", "openscad", "-o", "o.png"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(
        r.stderr.starts_with(
            "warning: twisting or unevenly scaling a 2-D combination or curves is drawn exact under `--facets openscad`\n --> t.csg:1:1"
        ),
        "{}",
        r.stderr
    );
    assert_eq!(run(&["--facets", "exact", "-o", "e.png", "-q"]).status, 0);
    let read = |f: &str| std::fs::read(dir.path().join(f)).unwrap();
    assert!(read("o.png") == read("e.png"), "not the exact picture");
    let strict = run(&["--facets", "openscad", "--strict", "-o", "s.png", "-q"]);
    assert_eq!(strict.status, 2, "{}", strict.stderr);
    assert!(!dir.path().join("s.png").exists());
}

/// Each file format by its own signature and header, read here by hand;
/// the BMP's pixels (uncompressed, bottom-up BGR rows padded to 4 bytes)
/// are the PNG's, pixel for pixel.
#[test]
fn the_output_format_follows_the_extension() {
    let (dir, _) = scene("ball.csg", SPHERE);
    let (w, h) = (37u32, 23u32);
    for name in [
        "a.png", "a.jpg", "a.JPEG", "a.bmp", "a.tif", "a.tiff", "a.webp",
    ] {
        let r = csgrt(
            dir.path(),
            &["ball.csg", "--size", "37x23", "-q", "-o", name],
        );
        assert_eq!(r.status, 0, "{name}: {}", r.stderr);
    }
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    let png = read("a.png");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&png[16..24], [w.to_be_bytes(), h.to_be_bytes()].concat());
    for jpeg in [read("a.jpg"), read("a.JPEG")] {
        assert_eq!(&jpeg[..3], [0xFF, 0xD8, 0xFF]);
        assert_eq!(&jpeg[jpeg.len() - 2..], [0xFF, 0xD9]);
    }
    for tiff in [read("a.tif"), read("a.tiff")] {
        assert_eq!(&tiff[..4], b"II*\0");
    }
    let webp = read("a.webp");
    assert_eq!((&webp[..4], &webp[8..12]), (&b"RIFF"[..], &b"WEBP"[..]));
    let bmp = read("a.bmp");
    assert_eq!(&bmp[..2], b"BM");
    let le = |at: usize| u32::from_le_bytes(bmp[at..at + 4].try_into().unwrap());
    assert_eq!((le(18), le(22), le(28) & 0xFFFF), (w, h, 24));
    let (offset, stride) = (le(10) as usize, (3 * w as usize).div_ceil(4) * 4);
    let decoded = image::load_from_memory(&png).unwrap().to_rgb8();
    for (x, y, p) in decoded.enumerate_pixels() {
        let at = offset + (h - 1 - y) as usize * stride + 3 * x as usize;
        assert_eq!([bmp[at + 2], bmp[at + 1], bmp[at]], p.0, "pixel {x},{y}");
    }
}

#[test]
fn an_output_in_no_known_format_is_refused_before_rendering() {
    let (dir, _) = scene("ball.csg", SPHERE);
    for (name, what) in [
        ("a.gif", "`.gif`"),
        ("a.PNGX", "`.pngx`"),
        ("noext", "no extension"),
    ] {
        let r = csgrt(dir.path(), &["ball.csg", "-q", "-o", name]);
        assert_eq!(r.status, 2);
        assert_eq!(
            r.stderr,
            format!(
                "error: {name}: {what} names no image format csgrt writes; expected .png, .jpg, \
                 .jpeg, .bmp, .tif, .tiff, .webp, .hdr or .exr (or `-` for PNG on standard \
                 output)\n"
            )
        );
        let r = csgrt(dir.path(), &["ball.csg", "-q", "--mask", name]);
        assert_eq!(r.status, 2, "{}", r.stderr);
    }
    assert_eq!(files(dir.path()), ["ball.csg"]);
}

#[test]
fn a_dash_writes_the_png_to_standard_output() {
    let (dir, _) = scene("ball.csg", SPHERE);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_csgrt"))
        .current_dir(dir.path())
        .args(["ball.csg", "--size", "40x30", "-o", "-"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(&out.stdout[..8], b"\x89PNG\r\n\x1a\n");
    let img = image::load_from_memory(&out.stdout).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (40, 30));
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.starts_with("csgrt: wrote <stdout> (40x30, adaptive: "),
        "{said}"
    );
    assert_eq!(files(dir.path()), ["ball.csg"]);
}

#[test]
fn a_model_that_cannot_be_read_is_named_in_plain_words() {
    let (dir, _) = scene("ball.csg", SPHERE);
    std::fs::create_dir(dir.path().join("folder.csg")).unwrap();
    for (model, want) in [
        ("nope.csg", "error: nope.csg: no such file\n"),
        ("folder.csg", "error: folder.csg: is a folder, not a file\n"),
    ] {
        let r = csgrt(dir.path(), &[model, "-q"]);
        assert_eq!((r.status, r.stderr.as_str()), (2, want));
    }
    std::fs::write(
        dir.path().join("latin1.csg"),
        b"cube(1);\nsphere(2); // \xe9t\xe9\n",
    )
    .unwrap();
    let r = csgrt(dir.path(), &["latin1.csg", "-q"]);
    assert_eq!(r.status, 2);
    assert_eq!(
        r.stderr,
        "error: byte 0xE9 is not UTF-8 text\n --> latin1.csg:2:15\n  |\n2 | sphere(2); // \u{FFFD}t\u{FFFD}\n  |               ^ expected a file saved as UTF-8 (as OpenSCAD writes it)\n"
    );
    assert_eq!(files(dir.path()), ["ball.csg", "folder.csg", "latin1.csg"]);
}

/// A `.scad` model goes through `openscad -o X.csg [-D ...] MODEL` on
/// PATH (a stand-in here that records its arguments and writes a fixed
/// export), and renders as that export does: the same bytes.
#[cfg(unix)]
#[test]
fn a_scad_model_is_exported_by_openscad_on_path_then_rendered() {
    let (dir, _) = scene("ref.csg", SPHERE);
    std::fs::write(dir.path().join("part.scad"), "r = 1; sphere(r);\n").unwrap();
    let bin = common::fake_openscad(&format!(
        "echo \"$@\" > args.txt\nprintf '{}' > \"$2\"",
        SPHERE.replace('\n', "\\n")
    ));
    let args = ["--size", "40x30", "-q", "-D", "r=2", "-D", "name=\"a b\""];
    let (status, said) = common::csgrt_with_path(
        dir.path(),
        bin.path(),
        &[&["part.scad"], &args[..]].concat(),
    );
    assert_eq!((status, said.as_str()), (0, ""));
    let asked = std::fs::read_to_string(dir.path().join("args.txt")).unwrap();
    let words: Vec<&str> = asked.split_whitespace().collect();
    assert_eq!(words[0], "-o");
    assert!(words[1].ends_with("/part.csg"), "{asked}");
    // `--viewall`, which OpenSCAD turns off (with a notice) exactly when
    // the program sets `$vp*`, and the echo of them after the user's -D.
    assert_eq!(
        &words[2..9],
        ["--viewall", "-D", "r=2", "-D", "name=\"a", "b\"", "-D"]
    );
    assert!(
        words[9].starts_with("__csgrt_view=echo(__csgrt_view=[$vpt,$vpr,$vpd,$vpf])"),
        "{asked}"
    );
    assert_eq!(words.last(), Some(&"part.scad"));
    let r = csgrt(dir.path(), &["ref.csg", "--size", "40x30", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    assert_eq!(read("part.png"), read("ref.png"));
    // The export itself is not left beside the model.
    assert_eq!(
        files(dir.path()),
        ["args.txt", "part.png", "part.scad", "ref.csg", "ref.png"]
    );
}

#[cfg(unix)]
#[test]
fn a_scad_model_without_openscad_or_that_it_refuses_is_a_clear_error() {
    let (dir, _) = scene("part.scad", "sphere(;\n");
    let nothing = tempfile::tempdir().unwrap();
    let (status, said) = common::csgrt_with_path(dir.path(), nothing.path(), &["part.scad", "-q"]);
    assert_eq!(status, 2);
    assert_eq!(
        said,
        "error: part.scad: reading a .scad program needs OpenSCAD, and `openscad` is not on \
         PATH; install it (Debian and Ubuntu: apt-get install -y openscad) or export the model \
         yourself (openscad -o part.csg part.scad) and render the .csg\n"
    );
    let bin =
        common::fake_openscad("echo \"ERROR: Parser error in file part.scad, line 1\" >&2\nexit 1");
    let (status, said) = common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q"]);
    assert_eq!(status, 2);
    assert_eq!(
        said,
        "error: OpenSCAD says: Parser error\n --> part.scad:1:1\n  |\n1 | sphere(;\n  | ^^^^^^^^ on this line (OpenSCAD gives no column)\n"
    );
    // An error OpenSCAD does not place: all it said.
    let bin = common::fake_openscad("echo \"Can't parse file 'part.scad'!\" >&2\nexit 1");
    let (status, said) = common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q"]);
    assert_eq!(status, 2);
    assert_eq!(
        said,
        "error: part.scad: OpenSCAD could not export it (exit status: 1); it said:\nCan't parse file 'part.scad'!\n"
    );
    // OpenSCAD's warnings are passed on, its progress lines not.
    let bin = common::fake_openscad(&format!(
        "echo 'Compiling design (CSG Products generation)...' >&2\n\
         echo \"WARNING: Ignoring unknown variable 'q'.\" >&2\n\
         printf '{}' > \"$2\"",
        SPHERE.replace('\n', "\\n")
    ));
    let (status, said) =
        common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q", "-o", "w.png"]);
    assert_eq!(
        (status, said.as_str()),
        (
            0,
            "warning: part.scad: OpenSCAD says: Ignoring unknown variable 'q'.\n"
        )
    );
    std::fs::remove_file(dir.path().join("w.png")).unwrap();
    assert_eq!(files(dir.path()), ["part.scad"]);
}

#[test]
fn definitions_are_for_scad_models_only_and_name_a_variable() {
    let (dir, _) = scene("s.csg", SPHERE);
    let r = csgrt(dir.path(), &["s.csg", "-D", "r=2", "-q"]);
    assert_eq!(
        (r.status, r.stderr.as_str()),
        (
            2,
            "error: s.csg: -D sets OpenSCAD variables, for a `.scad` model only\n"
        )
    );
    std::fs::write(dir.path().join("p.scad"), "sphere(1);\n").unwrap();
    let r = csgrt(dir.path(), &["p.scad", "-D", "=2", "-q"]);
    assert_eq!(
        (r.status, r.stderr.as_str()),
        (2, "error: -D =2: expected NAME=VALUE, as in -D width=20\n")
    );
    assert_eq!(files(dir.path()), ["p.scad", "s.csg"]);
}

/// OpenSCAD's `--imgsize W,H` is `--size WxH`: the same image, the same
/// limits; the two together are refused.
#[test]
fn imgsize_is_openscad_s_spelling_of_size() {
    let (dir, _) = scene("s.csg", SPHERE);
    let r = csgrt(
        dir.path(),
        &["s.csg", "--imgsize", "41,29", "-o", "a.png", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "41x29", "-o", "b.png", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    assert_eq!(read("a.png"), read("b.png"));
    for (arg, why) in [
        (
            "41x29",
            "`41x29` is not a size: expected W,H, as in 800,600",
        ),
        ("0,29", "`0,29`: width and height must be at least 1"),
        (
            "40000,2",
            "`40000,2`: each side may be at most 32768 pixels",
        ),
    ] {
        let r = csgrt(dir.path(), &["s.csg", "--imgsize", arg, "-q"]);
        assert_eq!(r.status, 2);
        let want = format!("error: invalid value '{arg}' for '--imgsize <W,H>': {why}\n");
        assert!(r.stderr.starts_with(&want), "{}", r.stderr);
    }
    let r = csgrt(
        dir.path(),
        &["s.csg", "--imgsize", "4,3", "--size", "4x3", "-q"],
    );
    assert_eq!(r.status, 2);
    assert!(r
        .stderr
        .starts_with("error: the argument '--imgsize <W,H>' cannot be used with '--size <WxH>'"));
    assert_eq!(files(dir.path()), ["a.png", "b.png", "s.csg"]);
}

/// `--colorscheme` gives what the file leaves uncoloured OpenSCAD's
/// scheme: its background and its face colour (here Starnight's, from
/// OpenSCAD 2021.01's `color-schemes/render/starnight.json`: background
/// #000000, face #ffffe0), under an ambient light of 1 and the default
/// ka = 0.2; `color` and the file's `background` stay.
#[test]
fn a_color_scheme_colours_what_the_file_does_not() {
    let text = "camera(eye = [0, -12, 0], lookat = [0, 0, 0]);\nambient_light([1, 1, 1]);\n\
                translate([-1.5, 0, 0]) cube(2, center = true);\n\
                color([1, 0, 0]) translate([1.5, 0, 0]) cube(2, center = true);\n";
    let (dir, _) = scene("s.csg", text);
    let px = |name: &str, x: u32, y: u32| {
        image::open(dir.path().join(name))
            .unwrap()
            .to_rgb8()
            .get_pixel(x, y)
            .0
    };
    let args = ["s.csg", "--size", "80x40", "--spp", "1", "-q"];
    for scheme in ["Starnight", "starnight", "STAR-NIGHT"] {
        let r = csgrt(
            dir.path(),
            &[&args[..], &["--colorscheme", scheme, "-o", "a.png"]].concat(),
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
        // ka 0.2 of the face colour, in linear values, encoded as sRGB.
        let face = |c: u32| srgb_byte(0.2 * srgb_decode(c as f64 / 255.0));
        assert_eq!(px("a.png", 20, 20), [face(0xff), face(0xff), face(0xe0)]);
        assert_eq!(px("a.png", 60, 20), [face(0xff), 0, 0]);
        assert_eq!(px("a.png", 2, 2), [0, 0, 0]);
    }
    // Without the option, Cornfield: #ffffe5 behind, #f9d72c faces.
    let r = csgrt(dir.path(), &[&args[..], &["-o", "b.png"]].concat());
    assert_eq!(r.status, 0, "{}", r.stderr);
    let face = |c: u32| srgb_byte(0.2 * srgb_decode(c as f64 / 255.0));
    assert_eq!(px("b.png", 20, 20), [face(0xf9), face(0xd7), face(0x2c)]);
    assert_eq!(px("b.png", 2, 2), [0xff, 0xff, 0xe5]);
    // The file's own background stays.
    std::fs::write(
        dir.path().join("g.csg"),
        format!("background([0.5, 0.5, 0.5]);\n{text}"),
    )
    .unwrap();
    let r = csgrt(
        dir.path(),
        &[
            "g.csg",
            "--size",
            "80x40",
            "-q",
            "--colorscheme",
            "Nature",
            "-o",
            "g.png",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(px("g.png", 2, 2), [128, 128, 128]);
    // An unknown name lists the schemes.
    let r = csgrt(dir.path(), &["s.csg", "--colorscheme", "Autumn"]);
    assert_eq!(r.status, 2);
    assert!(
        r.stderr.contains("expected Cornfield, Metallic, Sunset"),
        "{}",
        r.stderr
    );
}

/// A model's bytes never act on the terminal: control characters in a
/// message (an escape sequence that clears the screen and sets the
/// title, a bell) are written as escapes, and the caret still stands
/// under what it points at.
#[test]
fn messages_escape_the_control_characters_of_the_model() {
    let (dir, _) = scene("esc.csg", "cube(size = \u{1b}[2J \u{1b}]0;pwned\u{7} 2);\n");
    let r = csgrt(dir.path(), &["esc.csg", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(
        !r.stderr.chars().any(|c| c.is_control() && c != '\n'),
        "{:?}",
        r.stderr
    );
    let lines: Vec<&str> = r.stderr.lines().collect();
    assert_eq!(
        lines[3], r"1 | cube(size = \x1b[2J \x1b]0;pwned\x07 2);",
        "{}",
        r.stderr
    );
    let caret = lines[4].find('^').unwrap();
    assert_eq!(&lines[3][caret..caret + 4], r"\x1b", "{}", r.stderr);
    assert!(lines[0].contains(r"`\x1b`"), "{}", r.stderr);
    // A binary file is said to be one, its bytes escaped.
    std::fs::write(
        dir.path().join("bin.csg"),
        b"\x7fELF\x02\x01\x01\x00\x00\x1b[31m",
    )
    .unwrap();
    let r = csgrt(dir.path(), &["bin.csg", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(
        r.stderr
            .starts_with("error: byte 0x00 (NUL) in the file: it is not text\n --> bin.csg:1:8\n"),
        "{}",
        r.stderr
    );
    assert!(
        !r.stderr.chars().any(|c| c.is_control() && c != '\n'),
        "{:?}",
        r.stderr
    );
    assert_eq!(files(dir.path()), ["bin.csg", "esc.csg"]);
}

/// `--export-pov` or `--dump-scene` alone writes that file and no image
/// (the render is not needed); `-o` asks for the image too.
#[test]
fn an_export_alone_writes_no_image() {
    let (dir, _) = scene("s.csg", SPHERE);
    let r = csgrt(
        dir.path(),
        &[
            "s.csg",
            "--export-pov",
            "s.pov",
            "--dump-scene",
            "s.json",
            "-q",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(files(dir.path()), ["s.csg", "s.json", "s.pov"]);
    let r = csgrt(
        dir.path(),
        &["s.csg", "--export-pov", "t.pov", "-o", "t.png", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(
        files(dir.path()),
        ["s.csg", "s.json", "s.pov", "t.png", "t.pov"]
    );
}

/// OpenSCAD takes a `cube`'s size as a number or three numbers; anything
/// else (`[2, 2]`, a string, four numbers) it warns about and makes the
/// unit cube (its own export of such a cube reads `size = [1, 1, 1]`).
#[test]
fn a_cube_size_openscad_cannot_read_is_the_unit_cube_with_a_warning() {
    let dump = |text: &str| {
        let (dir, _) = scene("c.csg", text);
        let r = csgrt(
            dir.path(),
            &["c.csg", "-q", "--dump-scene", "d.json", "-o", "c.png"],
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
        (stats(dir.path(), "d.json")["root"].clone(), r.stderr)
    };
    let (unit, said) = dump("cube(size = [1, 1, 1]);\n");
    assert_eq!(said, "");
    for bad in ["[2, 2]", "\"a\"", "[1, 2, 3, 4]", "[1, \"a\", 2]", "true"] {
        let (root, said) = dump(&format!("cube(size = {bad});\n"));
        assert_eq!(root, unit, "{bad}");
        assert!(
            said.starts_with("warning: `size` of `cube` is neither a number nor a vector of 3 numbers; the cube is 1 × 1 × 1, as in OpenSCAD\n --> c.csg:1:13\n"),
            "{bad}: {said}"
        );
    }
}

/// A folder named as a model is said to be one, whatever its name.
#[test]
fn a_folder_is_no_model() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("part")).unwrap();
    let r = csgrt(dir.path(), &["part", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert_eq!(r.stderr, "error: part: is a folder, not a file\n");
    let r = csgrt(dir.path(), &["nothing", "-q"]);
    assert_eq!(r.stderr, "error: nothing: no such file\n");
}

/// `--help` ends with examples.
#[test]
fn help_shows_examples() {
    let dir = tempfile::tempdir().unwrap();
    let r = common::csgrt(dir.path(), &["--help"]);
    assert_eq!(r.status, 0);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_csgrt"))
        .arg("--help")
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("\nExamples:\n  csgrt part.scad "), "{text}");
    assert!(text.contains("--animate 24"), "{text}");
}

/// A `.scad` program's `$vpt`, `$vpr`, `$vpd` are the camera (OpenSCAD's
/// gimbal: the eye `$vpd` from `$vpt`, turned by `$vpr`), unless
/// `--camera` is given; they turn `--viewall` off, with a warning.
/// OpenSCAD reports them through the echo csgrt adds (a stand-in here
/// that says what OpenSCAD 2021.01 says for `$vpr = [90, 0, 0]; $vpd =
/// 60; $vpt = [1, 2, 3];`).
#[cfg(unix)]
#[test]
fn a_scad_program_s_view_is_the_camera() {
    let (dir, _) = scene(
        "v.scad",
        "$vpr = [90, 0, 0]; $vpd = 60; $vpt = [1, 2, 3]; cube(10);\n",
    );
    let bin = common::fake_openscad(
        "echo 'ECHO: __csgrt_view = [[1, 2, 3], [90, 0, 0], 60, 22.5]' >&2\n\
         echo 'WARNING: Viewall and autocenter disabled in favor of $vp*' >&2\n\
         printf 'cube(size = [10, 10, 10], center = false);\\n' > \"$2\"",
    );
    let eye = |args: &[&str]| {
        let (status, said) = common::csgrt_with_path(
            dir.path(),
            bin.path(),
            &[
                &[
                    "v.scad",
                    "-q",
                    "--size",
                    "40x30",
                    "--dump-scene",
                    "d.json",
                    "-o",
                    "v.png",
                ][..],
                args,
            ]
            .concat(),
        );
        assert_eq!(status, 0, "{said}");
        let d = stats(dir.path(), "d.json");
        let v = |k: &str| -> Vec<f64> {
            d["camera"][k]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        (v("eye"), v("lookat"), said)
    };
    // $vpr = [90, 0, 0]: the eye in front (−y) of $vpt, $vpd away.
    let (e, l, said) = eye(&[]);
    assert_eq!(said, "");
    let near = |a: &[f64], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9);
    assert!(
        near(&e, [1.0, -58.0, 3.0]) && near(&l, [1.0, 2.0, 3.0]),
        "{e:?} {l:?}"
    );
    let (_, _, said) = eye(&["--viewall"]);
    assert!(
        said.contains("--viewall and --autocenter give way to the view the program sets with $vp*"),
        "{said}"
    );
    // --camera wins.
    let (e, l, _) = eye(&["--camera", "0,0,0,0,0,0,100"]);
    assert!(
        near(&e, [0.0, 0.0, 100.0]) && near(&l, [0.0, 0.0, 0.0]),
        "{e:?} {l:?}"
    );
}

/// OpenSCAD's messages that name a line are placed there, in the user's
/// `.scad` (OpenSCAD gives no column: the caret takes the line); an error
/// in csgrt's reading of the export names the export, kept for it.
#[cfg(unix)]
#[test]
fn scad_messages_point_into_the_users_files() {
    let (dir, _) = scene("part.scad", "cube(10);\n  sphere(r=;\n");
    let bin = common::fake_openscad(
        "echo 'ERROR: Parser error: syntax error in file part.scad, line 2' >&2\n\
         echo \"Can't parse file 'part.scad'!\" >&2\nexit 1",
    );
    let (status, said) = common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q"]);
    assert_eq!(status, 2);
    assert_eq!(
        said,
        "error: OpenSCAD says: Parser error: syntax error\n --> part.scad:2:3\n  |\n2 |   sphere(r=;\n  |   ^^^^^^^^^^ on this line (OpenSCAD gives no column)\n"
    );
    // A warning at a line is placed too, and the render goes on; the
    // program's echoes are passed on as OpenSCAD prints them (not csgrt's
    // own echo of the view).
    let bin = common::fake_openscad(
        "echo \"WARNING: Ignoring unknown variable 'q' in file part.scad, line 1\" >&2\n\
         echo 'ECHO: \"width\", 20' >&2\n\
         echo 'ECHO: __csgrt_view = [[0, 0, 0], [0, 0, 0], 500, 22.5]' >&2\n\
         printf 'cube(size = [10, 10, 10], center = false);\\n' > \"$2\"",
    );
    let (status, said) =
        common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q", "-o", "w.png"]);
    assert_eq!(status, 0, "{said}");
    assert_eq!(
        said,
        "warning: OpenSCAD says: Ignoring unknown variable 'q'\n --> part.scad:1:1\n  |\n1 | cube(10);\n  | ^^^^^^^^^ on this line (OpenSCAD gives no column)\nECHO: \"width\", 20\n"
    );
    // csgrt's own error in the export: the export is kept and named.
    let bin = common::fake_openscad("printf 'cube(sise = 2);\\n' > \"$2\"");
    let (status, said) = common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q"]);
    assert_eq!(status, 2);
    let at = said.lines().nth(1).unwrap().trim_start_matches(" --> ");
    let kept = std::path::Path::new(at.strip_suffix(":1:6").expect(&said));
    assert!(kept.ends_with("part.csg") && kept.is_file(), "{said}");
    assert_eq!(std::fs::read_to_string(kept).unwrap(), "cube(sise = 2);\n");
    std::fs::remove_dir_all(kept.parent().unwrap()).unwrap();
    // OpenSCAD goes on past a failed assert with what it has (nothing
    // here): its error is a warning, its trace a note, and csgrt's own
    // warning about the empty export names the export, kept for it.
    let bin = common::fake_openscad(
        "echo \"ERROR: Assertion 'false' failed in file part.scad, line 1\" >&2\n\
         echo \"TRACE: called by 'assert' in file part.scad, line 1\" >&2\n\
         printf '' > \"$2\"",
    );
    let (status, said) =
        common::csgrt_with_path(dir.path(), bin.path(), &["part.scad", "-q", "-o", "w.png"]);
    assert_eq!(status, 0, "{said}");
    assert!(said.starts_with("warning: OpenSCAD reports an error, and renders what it has: Assertion 'false' failed\n --> part.scad:1:1\n"), "{said}");
    assert!(
        said.contains("\nnote: OpenSCAD says: called by 'assert'\n --> part.scad:1:1\n"),
        "{said}"
    );
    let at = said
        .lines()
        .find(|l| l.contains("csgrt-export-"))
        .expect(&said);
    let kept = std::path::Path::new(
        at.trim_start_matches(" --> ")
            .strip_suffix(":1:1")
            .expect(&said),
    );
    assert!(kept.is_file(), "{said}");
    std::fs::remove_dir_all(kept.parent().unwrap()).unwrap();
    assert_eq!(files(dir.path()), ["part.scad", "w.png"]);
}

/// The numbers of the `translate … scale k translate …` after the
/// leaf's matrix on `line`: (k, the centre).
fn clearance(line: &str) -> Option<(f64, f64)> {
    let (_, tail) = line.split_once(" translate ")?;
    let nums: Vec<f64> = tail
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .filter_map(|w| w.parse().ok())
        .collect();
    // -cx -cy -cz k cx cy cz
    Some((nums[3], nums[6]))
}

/// An extruded ring is a difference of two cylinders of one height: the
/// one taken away must reach past both caps it shares (POV-Ray draws a
/// solid disc where they coincide), and by no more than the clearance.
#[test]
fn a_part_taken_away_clears_the_caps_it_shares() {
    let src = csgrt::Source::new(
        "r.csg",
        "linear_extrude(height = 4) difference() { circle(r = 25); circle(r = 23); }\n",
    );
    let scene = csgrt::load_csg(&src).unwrap();
    let sdl = csgrt::export::pov::scene_sdl(&scene, &scene.view(80, 60), 80, 60, 5);
    let cyl: Vec<&str> = sdl.lines().filter(|l| l.contains("cylinder {")).collect();
    assert_eq!(cyl.len(), 2, "{sdl}");
    assert!(clearance(cyl[0]).is_none(), "{sdl}");
    let (k, cz) = clearance(cyl[1]).expect("a clearance on the part taken away");
    // z from 0 to 4 about the centre 2, scaled by k.
    let (lo, hi) = (cz - k * 2.0, cz + k * 2.0);
    assert!(lo < 0.0 && hi > 4.0, "{lo} {hi}");
    assert!(
        (k - 1.0) <= 2.0 * csgrt::export::pov::CLEARANCE * (1.0 + 1e-12),
        "{k}"
    );
    // Taken away from a part taken away: shrunk.
    let src = csgrt::Source::new(
        "n.csg",
        "difference() { cube(10); difference() { cube([5, 5, 10]); cube([2, 2, 10]); } }\n",
    );
    let scene = csgrt::load_csg(&src).unwrap();
    let sdl = csgrt::export::pov::scene_sdl(&scene, &scene.view(80, 60), 80, 60, 5);
    let ks: Vec<f64> = sdl
        .lines()
        .filter(|l| l.contains("box {"))
        .map(|l| clearance(l).map_or(1.0, |c| c.0))
        .collect();
    assert_eq!(
        ks,
        [
            1.0,
            1.0 + 2.0 * csgrt::export::pov::CLEARANCE,
            1.0 - 2.0 * csgrt::export::pov::CLEARANCE
        ],
        "{sdl}"
    );
}
