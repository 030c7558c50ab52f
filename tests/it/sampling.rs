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
/// `--spp 1`) or the mean of the 16 samples `--spp 16` takes there; it is
/// the latter wherever a neighbour's centre colour clearly differs by more
/// than the threshold (in linear values: the PNG's sRGB bytes decoded),
/// the former where every neighbour is clearly within it (8-bit rounding
/// leaves a band of 7/255 either way undecided: half a byte is at most
/// 0.0045 linear, times two pixels and three channels).
#[test]
fn adaptive_refines_exactly_where_neighbours_differ() {
    let (dir, _) = common::scene("s.csg", SCENE);
    let said = run(dir.path(), &["-o", "a.png"]);
    run(dir.path(), &["-q", "--spp", "1", "-o", "one.png"]);
    run(dir.path(), &["-q", "--spp", "16", "-o", "many.png"]);
    let (a, one, many) = (
        rgb(dir.path(), "a.png"),
        rgb(dir.path(), "one.png"),
        rgb(dir.path(), "many.png"),
    );
    let (w, h) = a.dimensions();
    let (mut refined, mut decided) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let c = one.get_pixel(x, y).0;
            let mut diff: f64 = 0.0;
            for ny in y.saturating_sub(1)..(y + 2).min(h) {
                for nx in x.saturating_sub(1)..(x + 2).min(w) {
                    let n = one.get_pixel(nx, ny).0;
                    let lin = |b: u8| common::srgb_decode(b as f64 / 255.0);
                    let d: f64 = (0..3).map(|k| (lin(c[k]) - lin(n[k])).abs()).sum();
                    diff = diff.max(d);
                }
            }
            let got = a.get_pixel(x, y).0;
            assert!(
                got == c || got == many.get_pixel(x, y).0,
                "pixel {x},{y} is neither the centre's nor the 16 samples' colour"
            );
            if diff > THRESHOLD + 7.0 / 255.0 {
                assert_eq!(got, many.get_pixel(x, y).0, "pixel {x},{y} not refined");
                refined += 1;
                decided += 1;
            } else if diff < THRESHOLD - 7.0 / 255.0 {
                assert_eq!(got, c, "pixel {x},{y} refined without cause");
                decided += 1;
            }
        }
    }
    assert!(
        refined > 100 && decided > (w * h) as usize * 9 / 10,
        "{refined} {decided}"
    );
    // The summary says how many pixels were sampled again.
    assert!(
        said.contains("adaptive: ") && said.contains(" of 6912 pixels at 16 spp"),
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
