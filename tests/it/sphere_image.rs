//! A lit sphere rendered by csgrt matches an image computed here,
//! independently, from the seed lecture's formulas (slides 6, 7, 13, 28),
//! the file's colours decoded from sRGB and the pixels encoded again (the
//! standard's formulas): within 2/255 per channel on every pixel.

use crate::common::{csgrt, scene, srgb_byte, srgb_decode};
use glam::DVec3;

const SCENE: &str = "\
camera(eye = [0.3, -5, 1], lookat = [0, 0, 0], up = [0, 0, 1], fov = 35);
background([0.1, 0.2, 0.3]);
ambient_light([0.3, 0.3, 0.3]);
directional_light([0.8, 0.7, 0.6], [-1, 2, -1.5]);
point_light([0.5, 0.5, 0.9], [3, -4, 4]);
material(color = [0.9, 0.4, 0.2], ka = 0.5, kd = 0.7, ks = 0.6, ns = 25)
  translate([0.2, 0.1, -0.1]) sphere(1.2);
";

/// The expected colour of the ray through image point (x, y).
fn expected(x: f64, y: f64, w: f64, h: f64) -> DVec3 {
    let (eye, lookat, up, fov) = (DVec3::new(0.3, -5.0, 1.0), DVec3::ZERO, DVec3::Z, 35.0f64);
    // Slide 6.
    let look = lookat - eye;
    let du = look.cross(up).normalize();
    let dv = look.cross(du).normalize();
    let fl = w / (2.0 * (0.5 * fov).to_radians().tan());
    let vp = look.normalize() * fl - 0.5 * (w * du + h * dv);
    let d = (x * du + y * dv + vp).normalize();
    // Slide 7: c = s − eye, v = d·c, b² = c·c − v², t = v − √(r² − b²).
    let (s, r) = (DVec3::new(0.2, 0.1, -0.1), 1.2);
    let c = s - eye;
    let v = d.dot(c);
    let disc = r * r - (c.dot(c) - v * v);
    if disc < 0.0 {
        // The background as given: sRGB, shown as it is.
        return DVec3::new(0.1, 0.2, 0.3).map(srgb_decode);
    }
    let t = v - disc.sqrt();
    let p = eye + t * d;
    let n = (p - s) / r;
    let view = -d;
    // Slide 13 / 28: ambient, then diffuse and specular per light. A convex
    // solid never shadows its own lit side.
    // The file's colour is sRGB; light adds up in linear values.
    let color = DVec3::new(0.9, 0.4, 0.2).map(srgb_decode);
    let (ka, kd, ks, ns) = (0.5, 0.7, 0.6, 25.0);
    let mut out = ka * DVec3::splat(0.3) * color;
    let lights = [
        (
            -DVec3::new(-1.0, 2.0, -1.5).normalize(),
            DVec3::new(0.8, 0.7, 0.6),
        ),
        (
            (DVec3::new(3.0, -4.0, 4.0) - p).normalize(),
            DVec3::new(0.5, 0.5, 0.9),
        ),
    ];
    for (l, il) in lights {
        let lambert = n.dot(l);
        if lambert > 0.0 {
            out += kd * lambert * color * il;
            let refl = 2.0 * lambert * n - l;
            let spec = view.dot(refl);
            if spec > 0.0 {
                out += ks * spec.powf(ns) * il;
            }
        }
    }
    out.clamp(DVec3::ZERO, DVec3::ONE)
}

#[test]
fn a_sphere_matches_the_seed_model_on_every_pixel() {
    let (dir, _) = scene("sphere.csg", SCENE);
    let (w, h) = (160u32, 120u32);
    let r = csgrt(
        dir.path(),
        &["sphere.csg", "--size", "160x120", "--spp", "1", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let img = image::open(dir.path().join("sphere.png"))
        .unwrap()
        .to_rgb8();
    let mut worst = 0;
    let mut lit = 0;
    for (x, y, px) in img.enumerate_pixels() {
        let e = expected(x as f64 + 0.5, y as f64 + 0.5, w as f64, h as f64);
        let want = [e.x, e.y, e.z].map(|c| srgb_byte(c) as i32);
        for ch in 0..3 {
            let diff = (px.0[ch] as i32 - want[ch]).abs();
            worst = worst.max(diff);
            assert!(
                diff <= 2,
                "pixel {x},{y} channel {ch}: got {:?}, expected {want:?}",
                px.0
            );
        }
        lit += (want != [26, 51, 77]) as u32;
    }
    // The sphere covers a good part of the frame, so the test means something.
    assert!(lit > 3000, "only {lit} sphere pixels");
    eprintln!("worst channel difference: {worst}/255");
}
