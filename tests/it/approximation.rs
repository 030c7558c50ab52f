//! The certified approximation (a hull, Minkowski sum or shadow of an
//! intersection or a difference): said once on stderr with its error in
//! pixels at the view, counted by `--stats-json`, never a warning; and
//! the pieces it is made of, against closed forms.

use crate::common::{csgrt, scene};
use csgrt::source::Source;

const HULL_OF_CUT_BALL: &str =
    "hull() intersection() { sphere(r = 10); cube(size = [16, 16, 16], center = true); }\n";

#[test]
fn the_note_names_the_statement_its_error_and_the_view_once() {
    let (dir, _) = scene("m.csg", HULL_OF_CUT_BALL);
    let r = csgrt(
        dir.path(),
        &[
            "m.csg",
            "--size",
            "80x60",
            "-q",
            "--strict",
            "--stats-json",
            "s.json",
        ],
    );
    // A note, not a warning: --strict renders past it.
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(r.stderr.matches("note: ").count(), 1, "{}", r.stderr);
    assert!(
        r.stderr
            .contains("note: `hull` of a 3-D intersection is approximated by convex polytopes"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("m.csg:1:1"), "{}", r.stderr);
    // 16 / 8192 of the node's width, and its share of a pixel here.
    assert!(
        r.stderr.contains("within 1.953e-3 of the exact solid"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("pixels at this view"), "{}", r.stderr);
    assert!(!r.stderr.contains("over half a pixel"), "{}", r.stderr);
    let stats = std::fs::read_to_string(dir.path().join("s.json")).unwrap();
    assert!(stats.contains("\"approximated_nodes\": 1"), "{stats}");
    // An exact hull says nothing and counts nothing.
    let (dir, _) = scene("e.csg", "hull() { sphere(r = 1); cube(size = 2); }\n");
    let r = csgrt(
        dir.path(),
        &["e.csg", "--size", "8x6", "-q", "--stats-json", "s.json"],
    );
    assert_eq!((r.status, r.stderr.as_str()), (0, ""));
    let stats = std::fs::read_to_string(dir.path().join("s.json")).unwrap();
    assert!(stats.contains("\"approximated_nodes\": 0"), "{stats}");
}

#[test]
fn a_view_past_the_bound_says_so() {
    let (dir, _) = scene("m.csg", HULL_OF_CUT_BALL);
    // The eye a hair (0.05) from the trim: there a pixel of a 40-pixel
    // picture is 0.0007 wide, and the error 1/8192 of 16 about 3 pixels.
    let r = csgrt(
        dir.path(),
        &[
            "m.csg",
            "--size",
            "40x30",
            "--spp",
            "1",
            "-q",
            "--camera",
            "8.05,4.25,4.25,8,4.24,4.24",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(r.stderr.contains("over half a pixel"), "{}", r.stderr);
}

/// The volume of polytopes.
fn volume(pieces: &[csgrt::geometry::polytope::Polytope]) -> f64 {
    pieces.iter().map(|p| p.volume()).sum()
}

/// The pieces of the scene's root.
fn pieces(text: &str, eps: f64, columns: bool) -> Vec<csgrt::geometry::polytope::Polytope> {
    let s = csgrt::load_csg(&Source::new("t.csg", text)).unwrap();
    let root = s.csg.root.unwrap();
    s.csg.convex_pieces(root, eps, 1e-9, columns).unwrap()
}

#[test]
fn a_plate_with_holes_is_cut_into_pieces_of_its_exact_volume() {
    // Boxes only: the pieces are exact, whether cells are halved or not.
    let mut text = String::from("difference() { cube(size = [40, 30, 4]);\n");
    for i in 0..6 {
        for j in 0..4 {
            let (x, y) = (2.0 + 6.5 * i as f64, 2.0 + 7.0 * j as f64);
            text += &format!("translate([{x}, {y}, -1]) cube(size = [4, 5, 6]);\n");
        }
    }
    text += "}\n";
    let want = 40.0 * 30.0 * 4.0 - 24.0 * 4.0 * 5.0 * 4.0;
    for columns in [false, true] {
        let p = pieces(&text, 1e-3, columns);
        assert!((volume(&p) - want).abs() < 1e-6, "{} {want}", volume(&p));
    }
}

#[test]
fn a_ball_minus_a_cylinder_is_within_the_faceting_of_its_volume() {
    // A ball of radius R drilled through by a hole of radius r is the
    // napkin ring of volume 4/3 π h³, h = √(R² − r²). The polytopes stay
    // within eps of the surfaces, so their volume is within the surface's
    // area times eps of it.
    let (big, small) = (10.0f64, 4.0f64);
    let text = format!(
        "difference() {{ sphere(r = {big}); cylinder(r = {small}, h = 30, center = true); }}\n"
    );
    let eps = 20.0 / 8192.0;
    let h = (big * big - small * small).sqrt();
    let exact = 4.0 / 3.0 * std::f64::consts::PI * h.powi(3);
    let v = volume(&pieces(&text, eps, false));
    // The surface (ball and hole) times eps bounds the change.
    let area =
        4.0 * std::f64::consts::PI * big * big + 2.0 * std::f64::consts::PI * small * 2.0 * h;
    assert!(
        (v - exact).abs() <= area * eps,
        "{v} against {exact} (within {})",
        area * eps
    );
    assert!((v - exact).abs() > 0.0);
}

/// The stderr of a scene csgrt renders (exit 0), and its count of
/// approximated nodes.
fn rendered(text: &str) -> (String, String) {
    let (dir, _) = scene("m.csg", text);
    let r = csgrt(
        dir.path(),
        &["m.csg", "--size", "40x30", "-q", "--stats-json", "s.json"],
    );
    assert_eq!(r.status, 0, "{text}: {}", r.stderr);
    let stats = std::fs::read_to_string(dir.path().join("s.json")).unwrap();
    (r.stderr, stats)
}

#[test]
fn the_plane_is_flattened_with_a_note_where_it_has_no_exact_form() {
    let cases = [
        (
            "linear_extrude(1) offset(delta = -1) union() { scale([2, 1]) circle(2); circle(1); }\n",
            "note: an `offset` of curves, ellipses, hulls or projections is approximated by straight polygons\n --> m.csg:1:19\n",
        ),
        (
            "linear_extrude(1, twist = 10) offset(r = 0.5) text(\"C\");\n",
            "note: a twist or scale of an offset of curved outlines is approximated by straight polygons\n --> m.csg:1:1\n",
        ),
        (
            "rotate_extrude() translate([20, 0]) offset(r = 0.5) text(\"C\");\n",
            "note: a turn of an offset of curved outlines is approximated by straight polygons\n --> m.csg:1:1\n",
        ),
        (
            "linear_extrude(1) offset(1) offset(r = 0.5) text(\"C\");\n",
            "note: an `offset` of curves, ellipses, hulls or projections is approximated by straight polygons\n --> m.csg:1:19\n",
        ),
        (
            "linear_extrude(height = 1, twist = 10) text(\"J\");\n",
            "note: a twist or uneven scale of curved outlines is approximated by straight polygons\n --> m.csg:1:1\n",
        ),
        (
            "rotate_extrude() projection() translate([5, 0, 0]) sphere(2);\n",
            "note: a turn of a projection is approximated by straight polygons\n --> m.csg:1:1\n",
        ),
        (
            "translate([1, 0, 0])\n  linear_extrude(1) minkowski() {\n    polygon([[0, 0], [4, 0], [4, 1], [1, 1], [1, 4], [0, 4]]);\n    difference() { square(2); circle(1); }\n  }\n",
            "note: a 2-D `minkowski` of shapes that are not convex is approximated by straight polygons\n --> m.csg:2:21\n",
        ),
    ];
    for (text, note) in cases {
        let (stderr, stats) = rendered(text);
        assert!(stderr.starts_with(note), "{text}: {stderr}");
        assert_eq!(stderr.matches("note: ").count(), 1, "{stderr}");
        assert!(
            stderr.contains("of the exact shape (1/8192 of its size)"),
            "{stderr}"
        );
        assert!(stats.contains("\"approximated_nodes\": 1"), "{stats}");
    }
    // A projection flattened for an offset, whose solid holds an
    // approximation of its own: both are said.
    let (stderr, stats) = rendered(
        "linear_extrude(1) offset(r = 1) projection() hull() difference() { sphere(5); cube(5); }\n",
    );
    assert!(
        stderr.contains("note: `hull` of a 3-D difference is approximated by convex polytopes"),
        "{stderr}"
    );
    assert!(
        stderr.contains(
            "note: an `offset` of curves, ellipses, hulls or projections is approximated"
        ),
        "{stderr}"
    );
    assert!(stats.contains("\"approximated_nodes\": 2"), "{stats}");
    // Straight shapes summed or offset with touching corners are exact:
    // nothing is said.
    for text in [
        "linear_extrude(1) minkowski() {\n    polygon([[0, 0], [4, 0], [4, 1], [1, 1], [1, 4], [0, 4]]);\n    polygon([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]);\n  }\n",
        "linear_extrude(1) offset(delta = -0.2) difference() { square(8); square(4); translate([4, 4]) square(2); }\n",
    ] {
        let (stderr, stats) = rendered(text);
        assert_eq!(stderr, "", "{text}");
        assert!(stats.contains("\"approximated_nodes\": 0"), "{stats}");
    }
}

/// The area of the section z = ½ of the scene's root, from the spans of
/// rays along x at the middles of `n` strips across [y0, y1] (exact for
/// widths constant on each strip; the midpoint rule's otherwise).
fn area(text: &str, y0: f64, y1: f64, n: usize) -> f64 {
    let s = csgrt::load_csg(&Source::new("t.csg", text)).unwrap();
    let root = s.csg.root.unwrap();
    let mut st = csgrt::stats::Stats::default();
    let h = (y1 - y0) / n as f64;
    (0..n)
        .map(|i| {
            let y = y0 + h * (i as f64 + 0.5);
            let ray = csgrt::geometry::Ray::new(glam::DVec3::new(-1e3, y, 0.5), glam::DVec3::X);
            s.csg
                .spans(root, &ray, 0.0, f64::INFINITY, &mut st)
                .iter()
                .map(|sp| sp.exit.t - sp.enter.t)
                .sum::<f64>()
                * h
        })
        .sum()
}

#[test]
fn two_ls_sum_to_their_staircase() {
    // L₁ = [0,4]×[0,1] ∪ [0,1]×[0,4], L₂ = [0,2]×[0,1] ∪ [0,1]×[0,2]:
    // their sum is the union of the rectangles' sums, [0,6]×[0,2],
    // [0,5]×[0,3], [0,3]×[0,5] and [0,2]×[0,6] — the staircase of area
    // 2·6 + 1·5 + 2·3 + 1·2 = 25. Straight: no flattening, exact.
    let text = "linear_extrude(1) minkowski() {\n    polygon([[0, 0], [4, 0], [4, 1], [1, 1], [1, 4], [0, 4]]);\n    polygon([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]);\n  }\n";
    let a = area(text, -1.0, 7.0, 800);
    assert!((a - 25.0).abs() < 1e-9, "{a}");
}

#[test]
fn an_ellipse_grown_round_has_steiner_s_area() {
    // A convex region K grown by r has area A + P·r + π r² (Steiner), P
    // its perimeter: for the ellipse of semi-axes 10 and 5, P by the
    // midpoint rule on 10⁶ steps of its arc length.
    let (a, b, r) = (10.0f64, 5.0f64, 1.5f64);
    let n = 1_000_000;
    let perimeter: f64 = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
            (a * a * t.sin().powi(2) + b * b * t.cos().powi(2)).sqrt()
        })
        .sum::<f64>()
        * std::f64::consts::TAU
        / n as f64;
    let pi = std::f64::consts::PI;
    let exact = pi * a * b + perimeter * r + pi * r * r;
    let text = "linear_extrude(1) offset(r = 1.5) scale([2, 1]) circle(r = 5);\n";
    // Flattened within eps = 20/8192: the area is within the outline's
    // length times eps, and the midpoint rule on 20,000 strips adds far
    // less (its error is of the width's curvature times h², but for the
    // strips at the tips, where it is of h^1.5).
    let eps = 20.0 / 8192.0;
    let v = area(text, -7.0, 7.0, 20_000);
    let slack = (perimeter + 2.0 * pi * r) * eps;
    assert!(
        (v - exact).abs() <= slack,
        "{v} against {exact} (within {slack})"
    );
    assert!(v < exact, "flattened inside: {v} against {exact}");
}

#[test]
fn turns_and_twists_are_cut_into_polytopes_with_a_note() {
    // A sum with a turned profile (not convex), a hull of a twist (no
    // support point), a torus less a box hulled: each renders, said once.
    for (text, note) in [
        (
            "minkowski() { rotate_extrude() polygon([[3, 0], [8, 0], [8, 2], [5, 4], [3, 4]]); sphere(0.5); }\n",
            "note: `minkowski` of a `rotate_extrude` is approximated by convex polytopes\n --> m.csg:1:1\n",
        ),
        (
            "hull() { linear_extrude(5, twist = 30) square([6, 2], center = true); sphere(1); }\n",
            "note: `hull` of a `linear_extrude` is approximated by convex polytopes\n --> m.csg:1:1\n",
        ),
        (
            "hull() difference() { torus(R = 10, r = 2); cube(20); }\n",
            "note: `hull` of a 3-D difference is approximated by convex polytopes\n --> m.csg:1:1\n",
        ),
    ] {
        let (stderr, stats) = rendered(text);
        assert!(stderr.starts_with(note), "{text}: {stderr}");
        assert_eq!(stderr.matches("note: ").count(), 1, "{stderr}");
        assert!(stats.contains("\"approximated_nodes\": 1"), "{stats}");
    }
}

/// An L of area 3 (the square [0, 2]² less [1, 2]²), 1 high, as a
/// polyhedron: not convex.
const ELL: &str = "polyhedron(points = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0], [0, 0, 1], [2, 0, 1], [2, 1, 1], [1, 1, 1], [1, 2, 1], [0, 2, 1]], faces = [[0, 1, 2, 3, 4, 5], [11, 10, 9, 8, 7, 6], [0, 6, 7, 1], [1, 7, 8, 2], [2, 8, 9, 3], [3, 9, 10, 4], [4, 10, 11, 5], [5, 11, 6, 0]]);";

#[test]
fn a_polyhedron_that_is_not_convex_is_cut_into_cells_of_its_volume() {
    // Exact: the cells of its faces' planes, whatever eps.
    let p = pieces(&format!("{ELL}\n"), 1.0, false);
    assert!(p.len() >= 2, "{} cells", p.len());
    assert!((volume(&p) - 3.0).abs() < 1e-9, "{}", volume(&p));
}

#[test]
fn two_polyhedra_that_are_not_convex_sum_to_their_staircase() {
    // L ⊕ L with L = [0,2]×[0,1] ∪ [0,1]×[0,2] (× [0, 1]): the union of the
    // rectangles' sums, [0,4]×[0,2], [0,3]×[0,3] and [0,2]×[0,4] (× [0, 2]):
    // a section of area 4·2 + 3·1 + 2·1 = 13, exactly (no faceting).
    let text = format!("minkowski() {{\n  {ELL}\n  {ELL}\n}}\n");
    let a = area(&text, -1.0, 5.0, 600);
    assert!((a - 13.0).abs() < 1e-9, "{a}");
}

#[test]
fn the_hull_of_a_difference_with_such_a_polyhedron_is_the_hull_of_what_is_left() {
    // The L less x ≥ 1.5, y ≤ 0.5: its hull's section is the polygon
    // (0,0), (1.5,0), (2,0.5), (2,1), (1,2), (0,2), of area 3.375.
    let text = format!(
        "hull() difference() {{\n  {ELL}\n  translate([1.5, -1, -1]) cube([1, 1.5, 3]);\n}}\n"
    );
    let a = area(&text, -0.5, 2.5, 3000);
    assert!((a - 3.375).abs() < 1e-5, "{a}");
}

#[test]
fn hulls_and_sums_nested_in_what_is_cut_are_their_parts_polytopes() {
    // The inner hull of two 2-cubes 4 apart is the box [0,6]×[0,2]×[0,2];
    // less z ≥ 1.5 it is [0,6]×[0,2]×[0,1.5], its own hull: the section
    // z = ½ has area 12. The inner sum of two cubes, [0,3]³, less x ≥ 2:
    // [0,2]×[0,3], area 6. Boxes only: exact.
    let hulled = "hull() difference() {\n  hull() { cube(2); translate([4, 0, 0]) cube(2); }\n  translate([-1, -1, 1.5]) cube(10);\n}\n";
    let a = area(hulled, -1.0, 3.0, 400);
    assert!((a - 12.0).abs() < 1e-9, "{a}");
    let summed = "hull() difference() {\n  minkowski() { cube(2); cube(1); }\n  translate([2, -1, -1]) cube(10);\n}\n";
    let a = area(summed, -1.0, 4.0, 500);
    assert!((a - 6.0).abs() < 1e-9, "{a}");
}

#[test]
fn a_mesh_that_is_not_closed_is_left_out_where_it_is_cut_as_openscad_leaves_it_out() {
    // A box with no lid has no inside: OpenSCAD 2021.01's render cannot
    // make it a Nef polyhedron ("The given mesh is not closed!") and
    // leaves it out, so a hull of its difference with a ball apart is the
    // ball, and a sum of that difference with a ball is the ball alone
    // (OpenSCAD's Minkowski sum of an empty part and a ball).
    let open = "polyhedron(points = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], faces = [[0, 1, 2, 3], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]]);";
    for (text, lo, hi) in [
        (
            format!("hull() {{ difference() {{ {open} cube(0.5); }} translate([3, 0, 0]) sphere(1); }}\n"),
            [2.0, -1.0, -1.0],
            [4.0, 1.0, 1.0],
        ),
        (
            format!("minkowski() {{ difference() {{ {open} cube(0.5); }} sphere(0.2); }}\n"),
            [-0.2; 3],
            [0.2; 3],
        ),
    ] {
        let scene = csgrt::load_csg(&Source::new("o.csg", &text)).unwrap();
        let b = scene.result_bounds();
        let far = (b.min - glam::DVec3::from(lo))
            .abs()
            .max((b.max - glam::DVec3::from(hi)).abs())
            .max_element();
        assert!(far < 1e-3, "{text}: {:?} {:?}", b.min, b.max);
    }
}
