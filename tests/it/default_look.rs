//! The default look (docs/LANGUAGE.md, "Default lights"), computed here
//! from the documented rig and the standard sRGB formulas: every pixel of
//! a cube on a plate, lit faces reaching the base colour, no face turned
//! from the light or in the key's shadow going dark.

use crate::common::{csgrt, scene, srgb_byte, srgb_decode_bytes, stats, DumpCamera};
use glam::DVec3;

/// The rig as the documentation gives it: (intensity, towards the light in
/// the camera's right, up, back axes, casts shadows), with an ambient of 1.
const RIG: [(f64, [f64; 3], bool); 3] = [
    (0.85, [-0.5, 0.5, 0.7], true),
    (0.15, [0.9, -0.1, 0.45], false),
    (0.25, [0.0, 1.0, 0.2], false),
];

/// The direction towards a light given in the camera's right, up and back
/// axes.
fn towards(cam: &DumpCamera, l: [f64; 3]) -> DVec3 {
    let [right, up, back] = cam.axes();
    (l[0] * right + l[1] * up + l[2] * back).normalize()
}

/// The Whitted colour (linear) of a point with normal `n` seen along
/// `dir`, colour `c` (linear), the default material (ka 0.2, kd 0.8, ks
/// 0.3, ns 30), the key light blocked or not.
fn shade(view: &DumpCamera, c: DVec3, n: DVec3, dir: DVec3, key_blocked: bool) -> DVec3 {
    let mut out = 0.2 * c;
    for &(i, l, shadows) in &RIG {
        let l = towards(view, l);
        let ndl = n.dot(l);
        // Only the key casts shadows.
        if ndl <= 0.0 || (shadows && key_blocked) {
            continue;
        }
        out += 0.8 * ndl * i * c;
        let r = 2.0 * ndl * n - l;
        let vr = (-dir).dot(r);
        if vr > 0.0 {
            out += DVec3::splat(0.3 * vr.powf(30.0) * i);
        }
    }
    out
}

#[test]
fn a_cube_on_a_plate_is_shaded_as_documented_with_soft_shadows() {
    // A 10 mm cube on a 40 × 40 × 1 plate: in the default view the key
    // (from the upper left) throws the cube's shadow to the lower right.
    let text = "translate([-20, -20, -1]) cube([40, 40, 1]);\ncube(10);\n";
    let (dir, _) = scene("p.csg", text);
    let r = csgrt(
        dir.path(),
        &[
            "p.csg",
            "--size",
            "240x180",
            "--spp",
            "1",
            "--dump-scene",
            "d.json",
            "-q",
            "-o",
            "p.png",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let d = stats(dir.path(), "d.json");
    let view = DumpCamera::of(&d["camera"]);
    let img = image::open(dir.path().join("p.png")).unwrap().to_rgb8();
    let base = srgb_decode_bytes(0xf9d72c);
    let key = towards(&view, RIG[0].1);
    // The nearest hit of a ray with an axis-aligned box, and its normal.
    let hit_box = |o: DVec3, dir: DVec3, lo: DVec3, hi: DVec3| -> Option<(f64, DVec3)> {
        let (mut t0, mut t1, mut n) = (0.0f64, f64::INFINITY, DVec3::ZERO);
        for a in 0..3 {
            let (near, far) = ((lo[a] - o[a]) / dir[a], (hi[a] - o[a]) / dir[a]);
            let (a0, a1) = (near.min(far), near.max(far));
            if a0 > t0 {
                t0 = a0;
                n = DVec3::ZERO;
                n[a] = -dir[a].signum();
            }
            t1 = t1.min(a1);
        }
        (t0 <= t1 && t0 > 0.0).then_some((t0, n))
    };
    let boxes = [
        (DVec3::new(-20.0, -20.0, -1.0), DVec3::new(20.0, 20.0, 0.0)),
        (DVec3::ZERO, DVec3::splat(10.0)),
    ];
    let first = |o: DVec3, dir: DVec3| {
        boxes
            .iter()
            .filter_map(|&(lo, hi)| hit_box(o, dir, lo, hi))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    };
    let (mut checked, mut shadowed, mut worst) = (0, 0, 0);
    let (mut top, mut darkest) = ([0u8; 3], 255u8);
    for (i, j, px) in img.enumerate_pixels() {
        let dir = view.ray(i as f64 + 0.5, j as f64 + 0.5);
        let Some((t, n)) = first(view.eye, dir) else {
            continue;
        };
        let p = view.eye + t * dir;
        // Pixels near an edge of a face, or of the shadow, are left out:
        // the exact answer there turns on a hair.
        let probe = |di: f64, dj: f64| {
            let q = view.ray(i as f64 + 0.5 + di, j as f64 + 0.5 + dj);
            first(view.eye, q).map(|(_, m)| m)
        };
        if [(-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0)]
            .iter()
            .any(|&(a, b)| probe(a, b) != Some(n))
        {
            continue;
        }
        let blocked = |q: DVec3| first(q + 1e-7 * n, key).is_some();
        let shifted = |a: f64, b: f64| {
            p + a * n.any_orthonormal_vector() + b * n.cross(n.any_orthonormal_vector())
        };
        let edge = [(-0.3, 0.0), (0.3, 0.0), (0.0, -0.3), (0.0, 0.3)]
            .iter()
            .any(|&(a, b)| blocked(shifted(a, b)) != blocked(p));
        if edge {
            continue;
        }
        let want = shade(&view, base, n, dir, blocked(p)).map(srgb_byte_f);
        for k in 0..3 {
            let diff = (px.0[k] as i32 - want[k] as i32).abs();
            worst = worst.max(diff);
            assert!(diff <= 1, "pixel {i},{j}: {:?} against {want:?}", px.0);
        }
        checked += 1;
        shadowed += blocked(p) as u32;
        if n == DVec3::Z && !blocked(p) {
            top = px.0;
        }
        darkest = darkest.min(px.0[0]);
    }
    assert!(checked > 10_000 && shadowed > 300, "{checked} {shadowed}");
    // Lit faces reach the base colour (#f9d72c): the unshaded top within
    // 3 % in every channel; nothing is darker than 45 % of its red.
    for (k, b) in [0xf9u8, 0xd7, 0x2c].iter().enumerate() {
        assert!(top[k] as f64 >= 0.97 * *b as f64, "top {top:?}");
    }
    assert!(darkest as f64 >= 0.45 * 249.0, "darkest red {darkest}");
    eprintln!("{checked} pixels, {shadowed} in shadow, worst {worst}/255");
}

fn srgb_byte_f(v: f64) -> f64 {
    srgb_byte(v) as f64
}
