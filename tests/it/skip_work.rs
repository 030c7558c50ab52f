//! csgrt skips work a scene does not need; the counters of --stats-json
//! show it.

use crate::common::{csgrt, scene, stats};
use std::path::Path;

fn counters(text: &str, size: &str) -> serde_json::Value {
    let (dir, _) = scene("s.csg", text);
    let r = csgrt(
        dir.path(),
        &[
            "s.csg",
            "--size",
            size,
            // One sample at each pixel centre, where the mask looks.
            "--spp",
            "1",
            "--stats-json",
            "st.json",
            "--mask",
            "m.png",
            "-q",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let mut s = stats(dir.path(), "st.json");
    let mask = image::open(dir.path().join("m.png")).unwrap().to_luma8();
    s["mask_hits"] = mask.pixels().filter(|p| p.0[0] == 255).count().into();
    s
}

#[test]
fn no_shadow_ray_where_the_light_is_behind_the_surface() {
    // A floor seen from above, lit only from below.
    let s = counters(
        "camera(eye = [0, -5, 5], lookat = [0, 0, 0]);\ndirectional_light([1, 1, 1], [0, 0, 1]);\nhalfspace();\n",
        "40x30",
    );
    assert!(s["mask_hits"].as_u64().unwrap() > 100);
    assert_eq!(s["shadow_rays"], 0);
}

#[test]
fn a_shadow_ray_stops_at_the_first_opaque_blocker() {
    // Fifty spheres stacked beside the shadow rays' path: they cost box
    // tests, not primitive tests.
    let mut text = String::from(
        "camera(eye = [0, 0, 30], lookat = [0, 0, 0], up = [0, 1, 0], fov = 3);\ndirectional_light([1, 1, 1], [0, 0, -1]);\nhalfspace();\n",
    );
    for i in 0..50 {
        text += &format!("translate([30, 0, {}]) sphere(0.4);\n", 1 + i);
    }
    // The camera sees only floor: every pixel casts one shadow ray up.
    let s = counters(&text, "20x20");
    let shadow = s["shadow_rays"].as_u64().unwrap();
    assert_eq!(shadow, 400, "one shadow ray a pixel");
    let prims = s["primitive_tests"].as_u64().unwrap();
    assert!(prims <= 2 * 400 + 2 * shadow, "{prims} primitive tests");
    // Fifty opaque discs right over the floor the camera sees: a shadow
    // ray stops at the first.
    let mut text = String::from(
        "camera(eye = [0, -1, 30], lookat = [0, 0, 0], fov = 3);\ndirectional_light([1, 1, 1], [0, 0, -1]);\nhalfspace();\n",
    );
    for i in 0..50 {
        text += &format!("translate([0, 0, {}]) cylinder(h = 0.5, r = 3);\n", 40 + i);
    }
    let s = counters(&text, "20x20");
    let shadow = s["shadow_rays"].as_u64().unwrap();
    assert_eq!(shadow, 400);
    let prims = s["primitive_tests"].as_u64().unwrap();
    // Each blocked shadow ray needs the halfspace, the first blocker and
    // at most a couple more: far fewer than the 50 discs in its way.
    assert!(
        prims <= 400 * 2 + shadow * 4,
        "{prims} primitive tests for {shadow} shadow rays"
    );
}

#[test]
fn no_secondary_ray_below_the_weight_cutoff() {
    let s = counters(
        "camera(eye = [0, -6, 0], lookat = [0, 0, 0]);\nmaterial(kr = 0.0019, kt = 0.0019) sphere(1);\n",
        "32x24",
    );
    assert_eq!(s["reflected_rays"], 0);
    assert_eq!(s["refracted_rays"], 0);
    let s = counters(
        "camera(eye = [0, -6, 0], lookat = [0, 0, 0]);\nmaterial(kr = 0.002, kt = 0.002) sphere(1);\n",
        "32x24",
    );
    assert!(
        s["reflected_rays"].as_u64().unwrap() > 0,
        "at 0.002 ≥ 1/512 they are cast"
    );
}

#[test]
fn one_normal_per_shaded_hit_and_none_for_misses() {
    let s = counters(
        "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\ndifference() { cube(2, center = true); sphere(1.3); }\ntranslate([0, 0, -1]) torus(R = 2, r = 0.3);\n",
        "64x48",
    );
    assert_eq!(s["normals_computed"], s["mask_hits"]);
}

#[test]
fn no_span_query_of_any_example_model_allocates() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for entry in std::fs::read_dir(root.join("models")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("csg") {
            continue;
        }
        let dir = tempfile::tempdir().unwrap();
        let r = csgrt(
            dir.path(),
            &[
                path.to_str().unwrap(),
                "-o",
                "x.png",
                "--size",
                "200x150",
                "--stats-json",
                "s.json",
                "-q",
            ],
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
        let s = stats(dir.path(), "s.json");
        assert_eq!(s["span_allocations"], 0, "{}", path.display());
    }
}

#[test]
fn a_ray_through_more_spans_than_the_scratch_holds_counts_its_allocation() {
    // A wall lit through thin transparent slabs, more of them than the
    // spans a thread reserves: its shadow rays need the full span list of
    // the slabs' union.
    let slabs: String = (0..csgrt::csg::SCRATCH_SPANS + 44)
        .map(|i| {
            format!(
                "translate([{}, -5, -5]) cube([0.1, 10, 10]);\n",
                i as f64 * 0.2
            )
        })
        .collect();
    let text = format!(
        "camera(eye = [65, 0, 0], lookat = [70, 0, 0], fov = 10);\npoint_light([1, 1, 1], position = [-100, 0, 0]);\ntranslate([70, -50, -50]) cube([1, 100, 100]);\ncolor([1, 1, 1, 0.5]) union() {{\n{slabs}}}\n"
    );
    let s = counters(&text, "4x3");
    assert!(s["span_allocations"].as_u64().unwrap() > 0, "{s}");
}

#[test]
fn hulls_and_sums_of_discs_and_balls_take_no_support_function_steps() {
    // Each of these has an exact form written out of primitives: a loft of
    // rounded rectangles and a box plus a cylinder (one disc), cones with
    // parallel axes (discs of several radii), a cylinder plus a ball (a
    // turned offset), and balls under the CSG export's 6-digit rotations.
    for text in [
        "hull() { cylinder(r = 2, h = 1); translate([9, 0, 4]) cylinder(r = 2, h = 1); translate([0, 7, 2]) cylinder(r = 2, h = 1); }",
        "minkowski() { cube([6, 4, 2]); cylinder(r = 1, h = 1); }",
        "hull() { cylinder(r1 = 3, r2 = 1, h = 4); translate([6, 1, 5]) cylinder(r = 2, h = 1); }",
        "minkowski() { cylinder(r1 = 3, r2 = 1, h = 4); sphere(r = 1); }",
        "hull() { sphere(r = 1); multmatrix([[0.809017, -0.587785, 0, 0], [0.587785, 0.809017, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) translate([5, 0, 1]) sphere(r = 1); translate([0, 4, 0]) sphere(r = 1); translate([1, 1, 4]) sphere(r = 1); }",
    ] {
        let s = counters(text, "40x30");
        assert!(s["mask_hits"].as_u64().unwrap() > 50, "{text}");
        assert_eq!(s["convex_steps"], 0, "{text}");
    }
}

#[test]
fn a_hull_cast_starts_from_its_neighbours_normal_the_same_on_any_thread() {
    // The hull of two ellipses of different shapes has no exact form: GJK
    // and Newton's method find where each ray enters and leaves it. A ray
    // starts from the normal the last ray of its row along nearly its
    // direction found (a row at a time, its memory emptied first), so the
    // counters, like the picture, do not depend on the threads; and it
    // takes fewer steps than a cast from scratch (16 a ray, primary and
    // shadow rays, before it did).
    let (dir, _) = scene(
        "s.csg",
        "camera(eye = [60, -70, 50], lookat = [0, 0, -8]);\n\
         hull() { scale([1, 0.5, 1]) cylinder(r = 29, h = 0.01); \
         translate([0, 0, -15]) scale([1, 0.55, 1]) cylinder(r = 24, h = 0.01); }\n",
    );
    let render = |threads: &str| {
        let (png, json) = (format!("{threads}.png"), format!("{threads}.json"));
        let args = [
            "s.csg",
            "--size",
            "80x60",
            "--spp",
            "1",
            "--threads",
            threads,
        ];
        let r = csgrt(
            dir.path(),
            &[&args[..], &["-q", "-o", &png, "--stats-json", &json]].concat(),
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
        let mut s = stats(dir.path(), &json);
        s.as_object_mut().unwrap().remove("render_seconds");
        (std::fs::read(dir.path().join(&png)).unwrap(), s)
    };
    let (one, s1) = render("1");
    let (three, s3) = render("3");
    assert_eq!(one, three);
    assert_eq!(s1, s3);
    let rays = s1["primary_rays"].as_u64().unwrap() + s1["shadow_rays"].as_u64().unwrap();
    let steps = s1["convex_steps"].as_u64().unwrap();
    assert!(
        rays > 3000 && steps < 10 * rays,
        "{steps} steps for {rays} rays"
    );
}

#[test]
fn a_hull_cut_in_part_is_one_polytope() {
    // The intersection is cut into polytopes (the certified
    // approximation), so the hull is approximated anyway: the cylinder
    // beside it and the ball a child rotated are cut too, and the hull
    // of all the corners is one polytope, with no support-function step.
    for text in [
        "hull() { intersection() { sphere(r = 5); cube(8, center = true); } translate([9, 0, 0]) cylinder(r = 2, h = 3); }",
        "hull() { difference() { cube(6); translate([6, 6, 6]) sphere(r = 3); } rotate([30, 0, 0]) translate([0, 9, 0]) scale([1, 2, 1]) sphere(r = 2); }",
    ] {
        let s = counters(text, "40x30");
        assert!(s["mask_hits"].as_u64().unwrap() > 50, "{text}");
        assert_eq!(s["convex_steps"], 0, "{text}");
        assert!(s["triangle_tests"].as_u64().unwrap() > 0, "{text}");
    }
}

#[test]
fn a_union_met_by_a_small_box_looks_only_at_what_lies_in_it() {
    // Eleven slivers fanning out from an apex 1,000 units away (a bevel
    // gear's teeth run to its cone's apex), met with a box at their far
    // ends, where they lie apart: every sliver's own box holds the whole
    // box met, but within it each holds only its own end, so a ray there
    // tests the few slivers it passes near (2.4 a ray; 4.0 when the
    // slivers' whole boxes were indexed).
    let slivers: String = (-5..=5)
        .map(|k| {
            let a = (k as f64 * 2.0f64).to_radians();
            let (c, s) = (a.cos(), a.sin());
            format!(
                "multmatrix([[{c}, {}, 0, -1000], [{s}, {c}, 0, 0], [0, 0, 1, -50], [0, 0, 0, 1]]) \
                 cube([1100, 4, 100], center = false);\n",
                -s
            )
        })
        .collect();
    let text = format!(
        "intersection() {{ union() {{\n{slivers}}} translate([60, -60, -5]) cube([40, 120, 10]); }}\n"
    );
    let s = counters(&text, "80x60");
    let rays = s["primary_rays"].as_u64().unwrap() + s["shadow_rays"].as_u64().unwrap();
    assert!(s["mask_hits"].as_u64().unwrap() > 100, "{text}");
    let tests = s["primitive_tests"].as_u64().unwrap();
    assert!(tests < 3 * rays, "{tests} primitive tests for {rays} rays");
}

#[test]
fn an_intersection_asks_its_cheap_child_first() {
    // A slab intersected with a column of 64 spheres that runs along the
    // view, the slab written last: every ray through the slab meets the
    // boxes of the spheres in front of and behind it, but only those the
    // slab leaves need their spans. Asked in the file's order, a ray
    // tested every sphere on its line (64 a ray); the slab first, the one
    // or two in the slab.
    let balls: String = (0..64)
        .map(|i| format!("translate([0, 0, {}]) sphere(1);\n", i as f64 * 1.5 - 48.0))
        .collect();
    let text = format!(
        "camera(eye = [0, 0, 60], lookat = [0, 0, 0], up = [0, 1, 0], fov = 4);\n\
         directional_light([1, 1, 1], [0, 0, -1]);\n\
         intersection() {{ union() {{\n{balls}}} translate([-5, -5, -0.5]) cube([10, 10, 1]); }}\n"
    );
    let s = counters(&text, "40x40");
    let rays = s["primary_rays"].as_u64().unwrap() + s["shadow_rays"].as_u64().unwrap();
    assert!(s["mask_hits"].as_u64().unwrap() > 100, "{text}");
    let tests = s["primitive_tests"].as_u64().unwrap();
    assert!(tests < 4 * rays, "{tests} primitive tests for {rays} rays");
}

#[test]
fn an_upright_rectangle_extruded_straight_is_drawn_as_its_box() {
    // Each extrusion renders to the same bytes as the `cube` placed where
    // it stands (the cube's own path, independent of the extrusion's):
    // a wrong corner, size or centring shows. A rectangle with its sides
    // off the axes, a tapered one and any other quadrilateral stay prisms.
    let camera = "camera(eye = [9, -14, 11], lookat = [1, 1, 0], fov = 40);\n";
    let render = |body: &str| {
        let (dir, _) = scene("s.csg", &format!("{camera}{body}\n"));
        let r = csgrt(
            dir.path(),
            &[
                "s.csg",
                "--size",
                "96x72",
                "-q",
                "-o",
                "p.png",
                "--dump-scene",
                "d.json",
            ],
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
        let dump = std::fs::read_to_string(dir.path().join("d.json")).unwrap();
        (std::fs::read(dir.path().join("p.png")).unwrap(), dump)
    };
    let same = [
        (
            "linear_extrude(height = 3) square([4, 2]);",
            "cube([4, 2, 3]);",
        ),
        (
            "linear_extrude(height = 3, center = true) square([4, 2], center = true);",
            "translate([-2, -1, -1.5]) cube([4, 2, 3]);",
        ),
        (
            "translate([1, 2, 0.5]) rotate([0, 0, 30]) linear_extrude(height = 3) \
             polygon([[0, 0], [0, 2], [4, 2], [4, 0]]);",
            "translate([1, 2, 0.5]) rotate([0, 0, 30]) cube([4, 2, 3]);",
        ),
        (
            "linear_extrude(height = 2) translate([-1, 0.5]) square([3, 1.5]);",
            "translate([-1, 0.5, 0]) cube([3, 1.5, 2]);",
        ),
    ];
    for (extruded, cube) in same {
        let (a, dump) = render(extruded);
        let (b, _) = render(cube);
        assert!(a == b, "{extruded} is not drawn as {cube}");
        assert!(dump.contains("\"cube\""), "{extruded}: {dump}");
    }
    for prism in [
        "linear_extrude(height = 3) rotate(20) square([4, 2]);",
        "linear_extrude(height = 3, scale = 0.5) square([4, 2]);",
        "linear_extrude(height = 3) polygon([[0, 0], [4, 0], [5, 2], [1, 2]]);",
    ] {
        let (_, dump) = render(prism);
        assert!(!dump.contains("\"cube\""), "{prism}: {dump}");
    }
}
