//! Numerical stability: coincident faces, A − A, deep nesting, degenerate
//! transforms and parts a million units from the origin.

use crate::common::{csgrt, scene, stats, Rng};
use csgrt::geometry::Ray;
use csgrt::stats::Stats;
use csgrt::{load_csg, Source};
use glam::{DAffine3, DMat3, DVec3};

fn load(text: &str) -> csgrt::Scene {
    load_csg(&Source::new("t.csg", text)).unwrap()
}

fn first(scene: &csgrt::Scene, o: DVec3, d: DVec3) -> Option<csgrt::csg::SurfaceHit> {
    scene.csg.first_hit(
        &Ray::new(o, d.normalize()),
        0.0,
        f64::INFINITY,
        &mut Stats::default(),
    )
}

/// The frame of `translate(T) rotate([17, 33, 41])`, as csgrt builds it.
fn frame() -> DAffine3 {
    let r = |axis: DVec3, deg: f64| DMat3::from_axis_angle(axis, f64::to_radians(deg));
    DAffine3::from_mat3_translation(
        r(DVec3::Z, 41.0) * r(DVec3::Y, 33.0) * r(DVec3::X, 17.0),
        DVec3::new(1000.0, -2000.0, 500.0),
    )
}

#[test]
fn a_cube_minus_a_cube_sharing_two_faces_is_an_open_tube_in_every_pixel() {
    let s = load(
        "translate([1000, -2000, 500]) rotate([17, 33, 41]) difference() {\n  cube([4, 4, 4]);\n  translate([1, 1, 0]) cube([2, 2, 4]);\n}\n",
    );
    let f = frame();
    let up = f.transform_vector3(DVec3::Z);
    let mut rng = Rng(7);
    for _ in 0..4000 {
        // Down through the hole, crossing the shared top face's plane at
        // (x, y) and drifting at most 0.02 by the bottom: the shared top
        // and bottom faces are open there.
        let (x, y) = (rng.range(1.03, 2.97), rng.range(1.03, 2.97));
        let tilt = DVec3::new(rng.range(-0.005, 0.005), rng.range(-0.005, 0.005), -1.0);
        let o = f.transform_point3(DVec3::new(x - 6.0 * tilt.x, y - 6.0 * tilt.y, 10.0));
        let d = f.transform_vector3(tilt);
        assert!(
            first(&s, o, d).is_none(),
            "a speckle in the hole at {x}, {y}"
        );
        // Down onto the wall's top: it is there, facing up.
        let (x, y) = (rng.range(0.01, 0.99), rng.range(0.01, 3.99));
        let o = f.transform_point3(DVec3::new(x, y, 10.0));
        let hit = first(&s, o, -up).expect("the wall's top");
        assert!((hit.t - 6.0).abs() < 1e-9, "t = {}", hit.t);
        assert!(hit.normal.dot(up) > 1.0 - 1e-12);
    }
}

#[test]
fn a_minus_a_is_empty_for_every_primitive() {
    for solid in [
        "sphere(2);",
        "cube([1, 2, 3]);",
        "cube(2, center = true);",
        "cylinder(h = 3, r = 1);",
        "cylinder(h = 3, r1 = 1, r2 = 0, center = true);",
        "torus(R = 2, r = 0.5);",
    ] {
        let text = format!(
            "translate([1e3, 2e3, -3e3]) rotate([10, 20, 30]) scale([1, 2, 0.5]) difference() {{ {solid} {solid} }}\n"
        );
        let s = load(&text);
        let mut rng = Rng(11);
        let c = DVec3::new(1e3, 2e3, -3e3);
        for _ in 0..2000 {
            let o = c + DVec3::new(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0), 9.0);
            let target = c + DVec3::new(
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
            );
            assert!(first(&s, o, target - o).is_none(), "{solid}: A − A hit");
        }
    }
}

#[test]
fn a_hundred_nested_differences_alternate_shells_exactly() {
    // sphere(100) − (sphere(99) − (sphere(98) − …)): shells of width 1.
    let mut text = String::from("sphere(1);");
    for r in 2..=100 {
        text = format!("difference() {{ sphere({r}); {text} }}");
    }
    let s = load(&text);
    let root = s.csg.root.unwrap();
    let ray = Ray::new(DVec3::new(0.0, 0.0, -200.0), DVec3::Z);
    let list = s
        .csg
        .spans(root, &ray, 0.0, f64::INFINITY, &mut Stats::default());
    // With 100 on the outside the solid is the radii [2k − 1, 2k]: a shell
    // between every odd radius and the even one above it, 50 of them, each
    // crossed twice.
    let mut want = Vec::new();
    for k in (1..=50).rev() {
        want.push((200.0 - 2.0 * k as f64, 200.0 - (2 * k - 1) as f64));
    }
    for k in 1..=50 {
        want.push((200.0 + (2 * k - 1) as f64, 200.0 + 2.0 * k as f64));
    }
    let got: Vec<(f64, f64)> = list.iter().map(|s| (s.enter.t, s.exit.t)).collect();
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(&want) {
        assert!(
            (g.0 - w.0).abs() < 1e-12 && (g.1 - w.1).abs() < 1e-12,
            "{g:?} vs {w:?}"
        );
    }
}

#[test]
fn degenerate_and_near_singular_transforms_give_no_nan() {
    let (dir, _) = scene(
        "d.csg",
        "camera(eye = [6, -8, 5], lookat = [0, 0, 0]);\n\
         scale([1, 1, 1e-12]) sphere(2);\n\
         translate([3, 0, 0]) scale([1e-9, 1, 1]) cube(1, center = true);\n\
         translate([-3, 0, 0]) multmatrix([[1, 1, 0, 0], [1, 1.000000000001, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(1);\n\
         translate([0, 3, 0]) scale([1, 1, 0]) cube(1);\n\
         translate([0, -3, 0]) material(kr = 0.5, kt = 0.5) scale([1e-6, 1e6, 1]) torus(R = 1, r = 0.2);\n",
    );
    let r = csgrt(
        dir.path(),
        &[
            "d.csg",
            "--size",
            "160x120",
            "--spp",
            "2",
            "--stats-json",
            "s.json",
            "-q",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    // The flattened cube is left out with a warning, as in OpenSCAD.
    assert!(
        r.stderr
            .contains("warning: this `cube` is flattened by a singular transform"),
        "{}",
        r.stderr
    );
    let s = stats(dir.path(), "s.json");
    assert_eq!(s["nonfinite_samples"], 0);
    assert!(s["normals_computed"].as_u64().unwrap() > 0);
    // The 1e-12-thin disc is hit where it is.
    let scene = load("scale([1, 1, 1e-12]) sphere(2);");
    let hit = first(&scene, DVec3::new(0.3, 0.2, 5.0), DVec3::NEG_Z).unwrap();
    assert!((hit.t - (5.0 - 1e-12 * (4.0f64 - 0.13).sqrt())).abs() < 1e-12);
    assert!(hit.normal.z > 0.999);
}

/// Renders `body` with its camera and lights moved by `shift`.
fn render_at(shift: [f64; 3], body: &str) -> Vec<u8> {
    let [x, y, z] = shift;
    let text = format!(
        "camera(eye = [{}, {}, {}], lookat = [{x}, {y}, {z}], fov = 40);\n\
         ambient_light([0.2, 0.2, 0.2]);\n\
         point_light([0.8, 0.8, 0.8], [{}, {}, {}]);\n\
         directional_light([0.3, 0.3, 0.3], [-1, 1, -2]);\n\
         translate([{x}, {y}, {z}]) {{ {body} }}\n",
        x + 7.0,
        y - 9.0,
        z + 6.0,
        x - 4.0,
        y - 6.0,
        z + 9.0,
    );
    let (dir, _) = scene("far.csg", &text);
    let r = csgrt(
        dir.path(),
        &[
            "far.csg",
            "--size",
            "120x90",
            "--stats-json",
            "s.json",
            "-q",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(stats(dir.path(), "s.json")["nonfinite_samples"], 0);
    image::open(dir.path().join("far.png"))
        .unwrap()
        .to_rgb8()
        .into_raw()
}

#[test]
fn a_lit_sphere_torus_and_box_a_million_units_out_shade_as_at_the_origin() {
    let body = "sphere(1.5); translate([3, 1, 0]) torus(R = 1.2, r = 0.4); translate([-4, -1, -1]) cube([2, 2, 2]); halfspace(offset = -1.5);";
    let near = render_at([0.0, 0.0, 0.0], body);
    let far = render_at([1e6, -1e6, 1e6], body);
    let worst = near
        .iter()
        .zip(&far)
        .map(|(a, b)| (*a as i32 - *b as i32).abs())
        .max()
        .unwrap();
    assert!(
        worst <= 2,
        "worst channel difference {worst}/255: acne or lost precision"
    );
    assert!(
        near.iter().any(|&v| v != near[0]),
        "the picture is not blank"
    );
}

#[test]
fn an_intersection_of_cubes_that_only_share_a_face_is_empty() {
    let s = load(
        "translate([1000, -2000, 500]) rotate([17, 33, 41]) intersection() {\n  cube([4, 4, 4]);\n  translate([4, 0, 0]) cube([3, 4, 4]);\n}\n",
    );
    let f = frame();
    let mut rng = Rng(3);
    for _ in 0..3000 {
        // Rays that cross the shared face x = 4 at random points and angles.
        let p = f.transform_point3(DVec3::new(
            4.0,
            rng.range(0.01, 3.99),
            rng.range(0.01, 3.99),
        ));
        let d = f.transform_vector3(DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ));
        assert!(
            first(&s, p - 10.0 * d.normalize(), d).is_none(),
            "a speckle on the shared face"
        );
    }
}

#[test]
fn shells_down_to_a_millionth_of_the_radius_are_crossed_exactly() {
    for (offset, thickness) in [(0.0, 1e-6), (1e3, 1e-6), (1e6, 1e-6), (0.0, 1e-3)] {
        let c = DVec3::new(offset, -0.5 * offset, 0.25 * offset);
        let inner = 1.0 - thickness;
        let s = load(&format!(
            "translate([{}, {}, {}]) difference() {{ sphere(1); sphere({inner:?}); }}",
            c.x, c.y, c.z
        ));
        let mut rng = Rng(5);
        for _ in 0..500 {
            // A chord at distance b from the centre, well inside the shell.
            let b = rng.range(0.0, 0.9);
            let o = c + DVec3::new(b, 0.0, -3.0);
            let hit = first(&s, o, DVec3::Z).expect("the outer sphere");
            let want = 3.0 - (1.0 - b * b).sqrt();
            assert!(
                (hit.t - want).abs() < 1e-9,
                "outer at {}, want {want}",
                hit.t
            );
            // Entering the shell: the next surface is the inner sphere, the
            // exact wall thickness along the chord away, not the same point.
            let err = csgrt::math::robust::point_error(hit.point, o, hit.t * DVec3::Z);
            let start = csgrt::math::robust::offset_origin(hit.point, hit.normal, err, DVec3::Z);
            let next = first(&s, start, DVec3::Z).expect("the inner sphere");
            // The new ray starts a little off the old one (moved along the
            // normal), so it meets the inner sphere at its own x.
            let rel = start - c;
            let exit_z = -(inner * inner - rel.x * rel.x - rel.y * rel.y).sqrt();
            let got_z = rel.z + next.t;
            assert!(
                (got_z - exit_z).abs() < 1e-9,
                "offset {offset}, thickness {thickness}: left at z {got_z}, the inner sphere is at {exit_z}"
            );
            let wall = (1.0 - b * b).sqrt() - (inner * inner - b * b).sqrt();
            assert!(
                next.t > 0.5 * wall,
                "re-hit after {} of a {wall} wall",
                next.t
            );
            assert!(next.normal.z > 0.0, "the inner sphere's wall faces the ray");
        }
    }
}

#[test]
fn a_ray_from_under_the_floor_leaves_through_the_part_standing_on_it() {
    // The halfspace's span ends exactly where the cube's begins: the union
    // merges them, so the first surface is the cube's top, not the floor.
    let mut text = String::from("halfspace();\ntranslate([-1, -1, 0]) cube(2);\n");
    for i in 0..10 {
        text += &format!("translate([{}, 5, 0]) sphere(0.5);\n", 2 * i);
    }
    let s = load(&text);
    let mut rng = Rng(9);
    for _ in 0..500 {
        // Drifting at most 0.025 sideways: the ray leaves through the top.
        let o = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            -rng.range(1.0, 20.0),
        );
        let d = DVec3::new(rng.range(-0.001, 0.001), rng.range(-0.001, 0.001), 1.0);
        let hit = first(&s, o, d).expect("the cube's top");
        let top = (2.0 - o.z) / d.normalize().z;
        assert!(
            (hit.t - top).abs() < 1e-9 * top,
            "t = {}, the top is at {top}",
            hit.t
        );
    }
}
