//! `projection(cut = true)` extruded: the spans of a ray are those of its
//! foot in the plane through the children, checked against closed forms —
//! the slice of a ball is a disc, of a turned box a rectangle — for rays
//! in every direction, straight down (the foot is one point) included.

use crate::common::Rng;
use csgrt::geometry::Ray;
use csgrt::stats::Stats;
use csgrt::{load_csg, Source};
use glam::DVec3;

fn spans_of(text: &str, o: DVec3, d: DVec3) -> Vec<(f64, f64)> {
    let scene = load_csg(&Source::new("p.csg", text)).unwrap();
    let csg = &scene.csg;
    let mut st = Stats::default();
    let ray = Ray::new(o, d);
    csg.spans(
        csg.root.unwrap(),
        &ray,
        f64::NEG_INFINITY,
        f64::INFINITY,
        &mut st,
    )
    .iter()
    .map(|s| (s.enter.t, s.exit.t))
    .collect()
}

/// The closed form: the t range where the ray is within the prism
/// x² + y² ≤ r², 0 ≤ z ≤ h.
fn disc_prism(r: f64, h: f64, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = if d.z == 0.0 {
        if (0.0..=h).contains(&o.z) {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            return None;
        }
    } else {
        let (a, b) = ((0.0 - o.z) / d.z, (h - o.z) / d.z);
        (a.min(b), a.max(b))
    };
    let a = d.x * d.x + d.y * d.y;
    if a == 0.0 {
        if o.x * o.x + o.y * o.y > r * r {
            return None;
        }
    } else {
        let b = o.x * d.x + o.y * d.y;
        let c = o.x * o.x + o.y * o.y - r * r;
        let disc = b * b - a * c;
        if disc < 0.0 {
            return None;
        }
        let q = disc.sqrt();
        lo = lo.max((-b - q) / a);
        hi = hi.min((-b + q) / a);
    }
    (lo < hi).then_some((lo, hi))
}

#[test]
fn the_slice_of_a_ball_is_its_disc_from_every_direction() {
    // A ball of radius 5 centred 3 above the plane: its slice is the disc
    // of radius 4, extruded 2 high.
    let text =
        "linear_extrude(height = 2) projection(cut = true) translate([0, 0, 3]) sphere(r = 5);";
    let mut rng = Rng(7);
    let mut checked = 0;
    for i in 0..400 {
        let o = DVec3::new(
            rng.range(-8.0, 8.0),
            rng.range(-8.0, 8.0),
            rng.range(-6.0, 8.0),
        );
        // Every tenth ray straight up or down, through the point test.
        let d = if i % 10 == 0 {
            DVec3::new(0.0, 0.0, if i % 20 == 0 { 1.0 } else { -1.0 })
        } else {
            // Towards a point near the solid, so that most rays meet it.
            let at = DVec3::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-1.0, 3.0),
            );
            (at - o).normalize()
        };
        let got = spans_of(text, o, d);
        match disc_prism(4.0, 2.0, o, d) {
            None => assert!(got.is_empty(), "ray {o} {d}: {got:?}"),
            Some((lo, hi)) => {
                assert_eq!(got.len(), 1, "ray {o} {d}: {got:?}");
                let scale = 10.0 * (1.0 + o.length());
                assert!(
                    (got[0].0 - lo).abs() <= 1e-12 * scale,
                    "{o} {d}: {:?} vs {lo}",
                    got[0]
                );
                assert!(
                    (got[0].1 - hi).abs() <= 1e-12 * scale,
                    "{o} {d}: {:?} vs {hi}",
                    got[0]
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 150, "{checked} rays met the solid");
}

#[test]
fn the_side_normal_is_the_slice_outline_normal() {
    // A ball seen from the side: the extruded disc's wall faces out
    // horizontally, though the ball's own normal there is tilted.
    let text =
        "linear_extrude(height = 2) projection(cut = true) translate([0, 0, 3]) sphere(r = 5);";
    let scene = load_csg(&Source::new("p.csg", text)).unwrap();
    let mut st = Stats::default();
    let ray = Ray::new(DVec3::new(-10.0, 0.0, 1.0), DVec3::X);
    let hit = scene
        .csg
        .first_hit(&ray, 0.0, f64::INFINITY, &mut st)
        .unwrap();
    assert!((hit.t - 6.0).abs() < 1e-12, "{}", hit.t);
    assert!(
        (hit.normal - DVec3::NEG_X).length() < 1e-12,
        "{}",
        hit.normal
    );
    // From above, the cap.
    let ray = Ray::new(DVec3::new(1.0, 1.0, 10.0), DVec3::NEG_Z);
    let hit = scene
        .csg
        .first_hit(&ray, 0.0, f64::INFINITY, &mut st)
        .unwrap();
    assert!((hit.t - 8.0).abs() < 1e-12, "{}", hit.t);
    assert!((hit.normal - DVec3::Z).length() < 1e-12, "{}", hit.normal);
}

#[test]
fn colours_below_a_projection_are_dropped() {
    let text = "color([1, 0, 0]) linear_extrude(height = 1) projection(cut = true) color([0, 0, 1]) sphere(r = 1);";
    let scene = load_csg(&Source::new("p.csg", text)).unwrap();
    let reds: Vec<u32> = scene.csg.prims.iter().map(|p| p.material).collect();
    assert!(reds.windows(2).all(|w| w[0] == w[1]), "{reds:?}");
    let m = &scene.materials[reds[0] as usize];
    assert_eq!(m.color, DVec3::new(1.0, 0.0, 0.0));
}

/// The closed form: the t range where the ray is within the prism
/// |x| + |y| ≤ r, 0 ≤ z ≤ h (four half-planes and the slab).
fn diamond_prism(r: f64, h: f64, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = if d.z == 0.0 {
        if (0.0..=h).contains(&o.z) {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            return None;
        }
    } else {
        let (a, b) = ((0.0 - o.z) / d.z, (h - o.z) / d.z);
        (a.min(b), a.max(b))
    };
    for (sx, sy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        // sx·x + sy·y ≤ r along the ray.
        let (f0, f1) = (sx * o.x + sy * o.y - r, sx * d.x + sy * d.y);
        if f1 == 0.0 {
            if f0 > 0.0 {
                return None;
            }
        } else if f1 > 0.0 {
            hi = hi.min(-f0 / f1);
        } else {
            lo = lo.max(-f0 / f1);
        }
    }
    (lo < hi).then_some((lo, hi))
}

/// Rays at `text` from all around (every tenth straight up or down, every
/// seventh along an axis of the plane) against a closed form.
fn check_rays(text: &str, exact: impl Fn(DVec3, DVec3) -> Option<(f64, f64)>) {
    let mut rng = Rng(11);
    let mut checked = 0;
    for i in 0..400 {
        let o = DVec3::new(
            rng.range(-8.0, 8.0),
            rng.range(-8.0, 8.0),
            rng.range(-6.0, 8.0),
        );
        let d = if i % 10 == 0 {
            DVec3::new(0.0, 0.0, if i % 20 == 0 { 1.0 } else { -1.0 })
        } else if i % 7 == 0 {
            DVec3::new(1.0, 0.0, 0.0)
        } else {
            let at = DVec3::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-1.0, 3.0),
            );
            (at - o).normalize()
        };
        let got = spans_of(text, o, d);
        match exact(o, d) {
            None => assert!(got.is_empty(), "ray {o} {d}: {got:?}"),
            Some((lo, hi)) => {
                assert_eq!(got.len(), 1, "ray {o} {d}: {got:?}");
                let scale = 10.0 * (1.0 + o.length());
                assert!(
                    (got[0].0 - lo).abs() <= 1e-12 * scale,
                    "{o} {d}: {:?} vs {lo}",
                    got[0]
                );
                assert!(
                    (got[0].1 - hi).abs() <= 1e-12 * scale,
                    "{o} {d}: {:?} vs {hi}",
                    got[0]
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 150, "{checked} rays met the solid");
}

#[test]
fn the_shadow_of_a_ball_is_its_great_disc() {
    check_rays(
        "linear_extrude(height = 2) projection(cut = false) translate([0, 0, 3]) sphere(r = 5);",
        |o, d| disc_prism(5.0, 2.0, o, d),
    );
}

#[test]
fn the_shadow_of_an_octahedron_mesh_is_its_square_across_shared_edges() {
    // Eight faces; the four above and the four below meet over the axes,
    // where the shadow must not open.
    check_rays(
        "linear_extrude(height = 2) projection(cut = false) polyhedron(points = [[5, 0, 0], [0, 5, 0], [-5, 0, 0], [0, -5, 0], [0, 0, 5], [0, 0, -5]], faces = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [1, 0, 5], [2, 1, 5], [3, 2, 5], [0, 3, 5]]);",
        |o, d| diamond_prism(5.0, 2.0, o, d),
    );
    // Turned and scaled off the grid, so that the edges shared over the
    // axes are crossed at rounded parameters.
    let (k, (sn, cs)) = (1.37, 17f64.to_radians().sin_cos());
    let back = |v: DVec3| DVec3::new((cs * v.x + sn * v.y) / k, (-sn * v.x + cs * v.y) / k, v.z);
    check_rays(
        "linear_extrude(height = 2) projection(cut = false) rotate([0, 0, 17]) scale([1.37, 1.37, 1]) polyhedron(points = [[5, 0, 0], [0, 5, 0], [-5, 0, 0], [0, -5, 0], [0, 0, 5], [0, 0, -5]], faces = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [1, 0, 5], [2, 1, 5], [3, 2, 5], [0, 3, 5]]);",
        |o, d| diamond_prism(5.0, 2.0, back(o), back(d)),
    );
    // Straight down on an edge shared over the axis, and through the apex.
    let text = "linear_extrude(height = 2) projection(cut = false) polyhedron(points = [[5, 0, 0], [0, 5, 0], [-5, 0, 0], [0, -5, 0], [0, 0, 5], [0, 0, -5]], faces = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [1, 0, 5], [2, 1, 5], [3, 2, 5], [0, 3, 5]]);";
    for o in [DVec3::new(2.0, 0.0, 9.0), DVec3::new(0.0, 0.0, 9.0)] {
        assert_eq!(spans_of(text, o, -DVec3::Z), vec![(7.0, 9.0)], "{o}");
    }
}
