//! `--viewall` frames the box of the result itself, as OpenSCAD frames its
//! mesh's (`Scene::result_bounds`): checked against boxes known in closed
//! form, where the parts' own boxes are far looser.

use csgrt::load_csg;
use csgrt::source::Source;
use glam::DVec3;

/// The result box of a scene, and how far each side may lie inside the
/// true one (the rays' grid finds the surface, never beyond it).
fn result_box(text: &str) -> (DVec3, DVec3) {
    let scene = load_csg(&Source::new("f.csg", text)).unwrap();
    let b = scene.result_bounds();
    (b.min, b.max)
}

fn close(got: DVec3, want: DVec3, tol: f64, what: &str) {
    assert!(
        (got - want).abs().max_element() <= tol,
        "{what}: {got} against {want}"
    );
}

#[test]
fn a_five_degree_sector_of_a_wide_ring_is_framed_as_the_sector() {
    // rotate_extrude(angle = 5) of the square [220, 230] x [0, 10]: the
    // sector from 0 to 5 degrees, x from 220 cos 5 to 230, y from 0 to
    // 230 sin 5, z from 0 to 10; the ring's own box is 460 wide.
    let (lo, hi) = result_box("rotate_extrude(angle = 5) translate([220, 0]) square([10, 10]);\n");
    let a = 5f64.to_radians();
    let step = 460.0 / 64.0 / 64.0;
    close(
        lo,
        DVec3::new(220.0 * a.cos(), 0.0, 0.0),
        2.0 * step,
        "low corner",
    );
    close(
        hi,
        DVec3::new(230.0, 230.0 * a.sin(), 10.0),
        2.0 * step,
        "high corner",
    );
}

#[test]
fn a_difference_is_framed_by_what_is_left() {
    // A 20-cube with all but its corner [0, 2]^3 cut away by three slabs:
    // the box of the first child is 20 wide, the result's 2.
    let (lo, hi) = result_box(
        "difference() {\n  cube(20);\n  translate([2, -1, -1]) cube(30);\n  translate([-1, 2, -1]) cube(30);\n  translate([-1, -1, 2]) cube(30);\n}\n",
    );
    close(lo, DVec3::ZERO, 1e-9, "low corner");
    close(
        hi,
        DVec3::splat(2.0),
        20.0 / 64.0 / 64.0 * 2.0,
        "high corner",
    );
}

#[test]
fn boxes_that_miss_each_other_frame_nothing_of_their_intersection() {
    // The intersection of two cubes apart is empty: only the ball is framed.
    let (lo, hi) = result_box(
        "intersection() { cube(1); translate([5, 0, 0]) cube(1); }\ntranslate([0, 0, 10]) sphere(1);\n",
    );
    close(lo, DVec3::new(-1.0, -1.0, 9.0), 1e-9, "low corner");
    close(hi, DVec3::new(1.0, 1.0, 11.0), 1e-9, "high corner");
}

#[test]
fn a_two_d_model_is_framed_flat() {
    // OpenSCAD's box of a 2-D model has no thickness; csgrt's slab is
    // framed in its middle plane.
    let (lo, hi) = result_box("square([4, 3]);\n");
    close(lo, DVec3::ZERO, 1e-9, "low corner");
    close(hi, DVec3::new(4.0, 3.0, 0.0), 1e-9, "high corner");
}

/// The default camera's box and where it looks.
fn default_framing(path: &str) -> (DVec3, DVec3, DVec3) {
    let text = std::fs::read_to_string(path).unwrap();
    let scene = load_csg(&Source::new(path, &text)).unwrap();
    let b = scene.framing_bounds();
    (b.min, b.max, scene.view(800, 600).lookat)
}

#[test]
fn the_default_camera_frames_the_sector_not_the_ring() {
    let (lo, hi, at) = default_framing("tests/scenes/ring_sector.csg");
    let a = 5f64.to_radians();
    let step = 460.0 / 64.0 / 64.0;
    let (want_lo, want_hi) = (
        DVec3::new(220.0 * a.cos(), 0.0, 0.0),
        DVec3::new(230.0, 230.0 * a.sin(), 10.0),
    );
    close(lo, want_lo, 2.0 * step, "low corner");
    close(hi, want_hi, 2.0 * step, "high corner");
    close(at, 0.5 * (want_lo + want_hi), 2.0 * step, "where it looks");
}

#[test]
fn the_default_camera_frames_what_the_slabs_leave() {
    // The ball of radius 14 at (10, 10, 10) with x < 4, y < 3, z < 5 reaches
    // x = 10 - sqrt(196 - 7² - 5²) (nearest at y = 3, z = 5), and so on; the
    // cube's corner gives the high sides.
    let (lo, hi, _) = default_framing("tests/scenes/cut_corner.csg");
    let want_lo = DVec3::new(
        10.0 - 122f64.sqrt(),
        10.0 - 135f64.sqrt(),
        10.0 - 111f64.sqrt(),
    );
    let want_hi = DVec3::new(4.0, 3.0, 5.0);
    // The high sides are exact far points (the cube's corner, in no slab).
    close(hi, want_hi, 1e-12, "high corner");
    // The low ones are the ball's tips between two slabs, which the rays
    // through a 64 x 64 grid over the box find within two steps of it; never
    // beyond (the rays find points of the surface).
    let slack = 2.0 * (want_hi - want_lo).max_element() / 64.0;
    close(lo, want_lo, slack, "low corner");
    assert!(
        lo.cmpge(want_lo - 1e-12).all(),
        "{lo} lies beyond {want_lo}"
    );
}

#[test]
fn a_floor_is_drawn_but_the_default_camera_frames_the_rest() {
    // A halfspace at the top level is unbounded: the bounded leaves' box.
    let scene = load_csg(&Source::new(
        "f.csg",
        "halfspace();\ntranslate([0, 0, 3]) sphere(2);\n",
    ))
    .unwrap();
    let b = scene.framing_bounds();
    close(b.min, DVec3::new(-2.0, -2.0, 1.0), 1e-12, "low corner");
    close(b.max, DVec3::new(2.0, 2.0, 5.0), 1e-12, "high corner");
}
