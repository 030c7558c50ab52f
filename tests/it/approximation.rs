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
