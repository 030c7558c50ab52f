//! The default sampling (adaptive anti-aliasing) and the linear outputs
//! (Radiance HDR, OpenEXR), checked against renders at fixed `--spp` and
//! the 8-bit image (sRGB), decoded by the `image` crate's readers.

use crate::common;
use crate::common::csgrt;
use std::path::Path;

const SCENE: &str = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\n\
    point_light([3, 3, 3], [2, -4, 5]);\n\
    difference() { cube(2, center = true); sphere(1.3); }\n\
    translate([0, -2, 0]) sphere(0.5);\n";

fn rgb(dir: &Path, name: &str) -> image::RgbImage {
    image::open(dir.join(name)).unwrap().to_rgb8()
}

fn run(dir: &Path, args: &[&str]) -> String {
    let mut all = vec!["s.csg", "--size", "96x72"];
    all.extend_from_slice(args);
    let r = csgrt(dir, &all);
    assert_eq!(r.status, 0, "{}", r.stderr);
    r.stderr
}

/// POV-Ray's threshold, in the tests' units: red + green + blue in [0, 1].
const THRESHOLD: f64 = 0.3;

/// Without `--spp`, each pixel is either the pixel centre's colour (as
/// `--spp 1`) or the mean of the 13 samples `--spp 13` takes there. It is
/// the latter exactly where a neighbour's centre colour differs by more
/// than the threshold *and* an edge crosses the pixel: one of its corners
/// differs from its centre or another corner by more than the threshold.
/// The corners are sampled independently here, as the pixel centres of a
/// render one pixel wider and higher whose horizontal field of view keeps
/// the focal length (tan(fov′/2) = tan(15°)·97/96). Colours are compared
/// in linear values (the PNG's sRGB bytes decoded); 8-bit rounding leaves a
/// band of 7/255 either way undecided (half a byte is at most 0.0045
/// linear, times two pixels and three channels).
#[test]
fn adaptive_refines_exactly_where_edges_cross() {
    let (dir, _) = common::scene("s.csg", SCENE);
    let said = run(dir.path(), &["-o", "a.png"]);
    run(dir.path(), &["-q", "--spp", "1", "-o", "one.png"]);
    run(dir.path(), &["-q", "--spp", "13", "-o", "many.png"]);
    let fov = 2.0 * (15f64.to_radians().tan() * 97.0 / 96.0).atan().to_degrees();
    let wider = SCENE.replace(
        "lookat = [0, 0, 0]",
        &format!("lookat = [0, 0, 0], fov = {fov}"),
    );
    std::fs::write(dir.path().join("c.csg"), wider).unwrap();
    let r = csgrt(
        dir.path(),
        &[
            "c.csg",
            "--size",
            "97x73",
            "--spp",
            "1",
            "-q",
            "-o",
            "corners.png",
        ],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let (a, one, many, corners) = (
        rgb(dir.path(), "a.png"),
        rgb(dir.path(), "one.png"),
        rgb(dir.path(), "many.png"),
        rgb(dir.path(), "corners.png"),
    );
    let lin = |p: &image::Rgb<u8>| p.0.map(|b| common::srgb_decode(b as f64 / 255.0));
    let differ = |p: [f64; 3], q: [f64; 3]| -> f64 { (0..3).map(|k| (p[k] - q[k]).abs()).sum() };
    let (w, h) = a.dimensions();
    let (mut refined, mut kept, mut decided) = (0, 0, 0);
    let band = 7.0 / 255.0;
    for y in 0..h {
        for x in 0..w {
            let c = lin(one.get_pixel(x, y));
            let mut near: f64 = 0.0;
            for ny in y.saturating_sub(1)..(y + 2).min(h) {
                for nx in x.saturating_sub(1)..(x + 2).min(w) {
                    near = near.max(differ(c, lin(one.get_pixel(nx, ny))));
                }
            }
            let mut five = vec![c];
            for (cx, cy) in [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)] {
                five.push(lin(corners.get_pixel(cx, cy)));
            }
            let mut crossed: f64 = 0.0;
            for i in 0..5 {
                for j in 0..i {
                    crossed = crossed.max(differ(five[i], five[j]));
                }
            }
            let got = a.get_pixel(x, y).0;
            let (centre, mean) = (one.get_pixel(x, y).0, many.get_pixel(x, y).0);
            assert!(
                got == centre || got == mean,
                "pixel {x},{y} is neither the centre's nor the 13 samples' colour"
            );
            if near > THRESHOLD + band && crossed > THRESHOLD + band {
                assert_eq!(got, mean, "pixel {x},{y} not refined");
                refined += 1;
                decided += 1;
            } else if near < THRESHOLD - band || crossed < THRESHOLD - band {
                assert_eq!(got, centre, "pixel {x},{y} refined without cause");
                if near > THRESHOLD + band && centre != mean {
                    kept += 1;
                }
                decided += 1;
            }
        }
    }
    // Many pixels are refined, and many near an edge keep their centre
    // (the corners' saving) though their 13 samples' mean differs.
    assert!(
        refined > 100 && kept > 30 && decided > (w * h) as usize * 9 / 10,
        "{refined} {kept} {decided}"
    );
    // The summary says how many pixels were sampled again.
    assert!(
        said.contains("adaptive: ") && said.contains(" of 6912 pixels at 13 spp"),
        "{said}"
    );
    // The same bytes for any thread count.
    run(dir.path(), &["-q", "--threads", "1", "-o", "a1.png"]);
    run(dir.path(), &["-q", "--threads", "3", "-o", "a3.png"]);
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    assert_eq!(read("a1.png"), read("a.png"));
    assert_eq!(read("a3.png"), read("a.png"));
}

/// EXR holds the linear radiance as 32-bit floats: at one sample a pixel,
/// clamped to [0, 1] and rounded, it is the 8-bit image; and it is above 1
/// where the PNG saturates. HDR (RGBE, an 8-bit mantissa) agrees within its
/// precision. With more samples a pixel's bytes are the mean of clamped
/// samples, its radiance the mean of unclamped ones: they differ only
/// where some sample saturates.
#[test]
fn hdr_and_exr_hold_the_linear_radiance() {
    let (dir, _) = common::scene("s.csg", SCENE);
    for (args, out) in [
        (&["--spp", "1"][..], "1"),
        (&["--spp", "4"], "4"),
        (&[], "a"),
    ] {
        for ext in ["png", "exr", "hdr"] {
            let name = format!("{out}.{ext}");
            let mut all = args.to_vec();
            all.extend_from_slice(&["-q", "-o", &name]);
            run(dir.path(), &all);
        }
        let png = rgb(dir.path(), &format!("{out}.png"));
        let magic = std::fs::read(dir.path().join(format!("{out}.exr"))).unwrap();
        assert_eq!(
            &magic[..4],
            &[0x76, 0x2f, 0x31, 0x01],
            "OpenEXR's magic number"
        );
        let magic = std::fs::read(dir.path().join(format!("{out}.hdr"))).unwrap();
        assert!(magic.starts_with(b"#?RADIANCE"), "Radiance's header");
        // RGBE rounds each channel to 1/128 of the pixel's largest: not to bytes.
        for (ext, tol, share) in [("exr", 1e-6, 0.99), ("hdr", 1.0 / 128.0, 0.0)] {
            let f = image::open(dir.path().join(format!("{out}.{ext}")))
                .unwrap()
                .to_rgb32f();
            assert_eq!(f.dimensions(), png.dimensions());
            let (mut exact, mut over) = (0, 0);
            for (p, q) in f.pixels().zip(png.pixels()) {
                // RGBE shares one exponent among a pixel's channels.
                let top = p.0.iter().fold(1e-3f64, |a, &c| a.max(c as f64));
                for k in 0..3 {
                    let v = p[k] as f64;
                    assert!(v.is_finite() && v >= 0.0);
                    over += (v > 1.0) as usize;
                    // The linear values the PNG's sRGB byte stands for.
                    let b = q[k] as f64;
                    let lo = common::srgb_decode(((b - 0.5) / 255.0).max(0.0));
                    let hi = common::srgb_decode((b + 0.5) / 255.0);
                    // Encoded as sRGB and rounded to bytes, the radiance
                    // is the PNG, up to the format's own precision
                    // (relative for RGBE).
                    let want = v.clamp(0.0, 1.0);
                    let slack = tol * top + 1e-9;
                    if out == "1" {
                        assert!(
                            want >= lo - slack && want <= hi + slack,
                            "{ext}: {v} against {}",
                            q[k]
                        );
                    } else {
                        // The mean of clamped samples is at most the
                        // clamped mean.
                        assert!(lo <= want + slack, "{ext} {out}: {v} against {}", q[k]);
                    }
                    exact += (common::srgb_byte(want) == q[k]) as usize;
                }
            }
            let n = 3 * f.pixels().len();
            if out == "1" {
                assert!(
                    exact as f64 >= share * n as f64,
                    "{ext}: {exact} of {n} exact"
                );
            }
            assert!(
                over > 0,
                "{ext}: the bright light leaves some radiance above 1"
            );
        }
    }
    // A mask is 8-bit: HDR and EXR are refused for it, before rendering.
    let r = csgrt(
        dir.path(),
        &["s.csg", "-q", "-o", "m.png", "--mask", "m.exr"],
    );
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("m.exr: a mask is an 8-bit grey image"),
        "{}",
        r.stderr
    );
    assert!(!dir.path().join("m.png").exists());
}
