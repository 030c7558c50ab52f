//! Rendering: camera rays → CSG queries → shading → an 8-bit image.
//!
//! Shading adds light in linear values (the scene's colours were decoded
//! from sRGB when it was built); each pixel's bytes are its linear colour
//! encoded as sRGB ([`srgb::byte`]), and HDR and EXR files keep the linear
//! radiance itself.
//!
//! Rows are rendered in parallel with rayon; every pixel depends only on
//! its own coordinates, so the bytes are the same for any thread count.

pub mod adaptive;
pub mod camera;
pub mod footprint;
pub mod probe;
pub mod sampler;
pub mod shade;

use crate::geometry::coherence::coherent;
use crate::math::srgb;
use crate::scene::{Light, Scene};
use crate::stats::Stats;
pub use adaptive::{Adaptive, ADAPTIVE_SPP, ADAPTIVE_THRESHOLD};
use camera::Camera;
use footprint::Footprint;
use glam::DVec3;
use rayon::prelude::*;
use shade::Shader;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel; with `adaptive`, the samples of a pixel that is
    /// sampled again.
    pub spp: u32,
    pub max_depth: u32,
    /// Adaptive anti-aliasing: see [`Adaptive`].
    pub adaptive: Option<Adaptive>,
    /// Keep each pixel's linear radiance (for HDR and EXR files).
    pub radiance: bool,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            width: 800,
            height: 600,
            spp: 1,
            max_depth: 5,
            adaptive: None,
            radiance: false,
        }
    }
}

/// An 8-bit RGB image, row-major from the top left, and on request the
/// linear radiance it was rounded from.
pub struct Rendered {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
    /// Linear RGB per pixel (three `f32` each), when
    /// [`Settings::radiance`] asked for it; else empty.
    pub radiance: Vec<f32>,
    /// The pixels adaptive anti-aliasing sampled again.
    pub refined: u64,
    pub stats: Stats,
}

/// Whether every component of `a` and `b` is finite: each times zero is
/// zero (NaN for ±∞ and NaN), and so is their sum — one test, not the six
/// branches of `is_finite` on each (a unit test compares them).
#[inline]
fn both_finite(a: DVec3, b: DVec3) -> bool {
    let z = a * 0.0 + b * 0.0;
    z.x + z.y + z.z == 0.0
}

/// What a render tells of its progress, counted in samples (camera rays):
/// the samples of a pass once it is planned, then each row's as it is
/// done. Adaptive anti-aliasing plans its second pass only when the first
/// is done, so the total grows once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    Planned(u64),
    Done(u64),
}

/// Renders the scene, telling `progress` how far it is.
pub fn render(scene: &Scene, s: &Settings, progress: &(dyn Fn(Progress) + Sync)) -> Rendered {
    let hooks = Hooks {
        progress,
        stop: &|| false,
        first_pass: &|_| {},
    };
    render_with(scene, s, &hooks).expect("a render nothing stops")
}

/// What a caller may ask of a render besides its picture (an interactive
/// view's: `csgrt view`).
pub struct Hooks<'a> {
    /// Told how far the render is.
    pub progress: &'a (dyn Fn(Progress) + Sync),
    /// Asked before each row is begun: `true` abandons the render.
    pub stop: &'a (dyn Fn() -> bool + Sync),
    /// Shown the picture of adaptive anti-aliasing's first pass (a sample
    /// at each pixel's centre, 8-bit RGB) before the second pass begins.
    pub first_pass: &'a (dyn Fn(&[u8]) + Sync),
}

/// [`render`] with [`Hooks`]: `None` when `stop` abandoned it. A render
/// that is not stopped is the same picture, bit for bit, as [`render`]'s.
pub fn render_with(scene: &Scene, s: &Settings, hooks: &Hooks) -> Option<Rendered> {
    let (progress, stop) = (hooks.progress, hooks.stop);
    let spec = scene.view(s.width, s.height);
    let cam = Camera::new(&spec, s.width, s.height);
    let lights = scene.lights_seen_by(&spec);
    // The line families the rays come in: through the eye, or along the
    // orthographic view; along each directional light's shadow rays.
    let mut dirs: Vec<DVec3> = lights.iter().filter_map(Light::shadow_direction).collect();
    dirs.extend(cam.parallel);
    let eye = cam.parallel.is_none().then_some(cam.eye);
    let viewed = scene.csg.viewed(eye, &dirs);
    let csg = viewed.as_ref().unwrap_or(&scene.csg);
    let shader = Shader::new(scene, csg, &lights, s.max_depth);
    // Where the scene's box is seen: a sample outside it sees the
    // background, as its ray would.
    let seen = Footprint::of(&cam, &csg.bounds(), s.width, s.height);
    let background = (scene.background, scene.background);
    // A sample of the picture, its ray cast only if `cast` (non-finite
    // ones counted, and `None`).
    let sample = |x: f64, y: f64, st: &mut Stats, cast: bool| {
        let (c, r) = if cast {
            st.primary_rays += 1;
            shader.primary(&cam.ray(x, y), st)
        } else {
            st.screen_culled += 1;
            background
        };
        if both_finite(c, r) {
            Some((c, r))
        } else {
            st.nonfinite_samples += 1;
            None
        }
    };
    // The mean of a pixel's `n` samples (non-finite ones counted, not
    // summed): of their colours, and of their radiance before the last
    // clamp.
    let pixel = |x: u32, y: u32, n: u32, st: &mut Stats, cast: bool| {
        if n == 1 {
            // The sum of one sample, divided by one: the same bits (zero
            // plus the sample, which turns −0 into +0, as the sum does).
            let (c, r) = sample(x as f64 + 0.5, y as f64 + 0.5, st, cast).unwrap_or_default();
            return (DVec3::ZERO + c, DVec3::ZERO + r);
        }
        let (mut sum, mut lin) = (DVec3::ZERO, DVec3::ZERO);
        for (ox, oy) in sampler::offsets(x, y, n) {
            if let Some((c, r)) = sample(x as f64 + ox, y as f64 + oy, st, cast) {
                sum += c;
                lin += r;
            }
        }
        (sum / n as f64, lin / n as f64)
    };
    let w = s.width as usize;
    let keep = s.radiance || s.adaptive.is_some();
    let mut rgb = vec![0u8; 3 * w * s.height as usize];
    let mut lin = vec![0f32; if keep { rgb.len() } else { 0 }];
    let first = if s.adaptive.is_some() { 1 } else { s.spp };
    progress(Progress::Planned(
        s.width as u64 * s.height as u64 * first as u64,
    ));
    // A pixel no ray is cast for is the background's: found once (its
    // bytes, its radiance and the counters of its samples) and copied.
    let mut culled_st = Stats::default();
    let (mut culled_rgb, mut culled_lin) = ([0u8; 3], [0f32; 3]);
    put(
        &mut culled_rgb,
        &mut culled_lin,
        0,
        pixel(0, 0, first, &mut culled_st, false),
    );
    // Each row's columns cast: every sample of a pixel lies in its square,
    // which `Footprint::columns` grows by its margin.
    let cast: Vec<std::ops::Range<u32>> = (0..s.height)
        .map(|y| seen.as_ref().map_or(0..s.width, |f| f.columns(y, s.width)))
        .collect();
    // Each row is written in place by whichever thread takes it; the
    // counters are sums and maxima, the same in any order.
    let mut stats = rows(&mut rgb, &mut lin, w, |y, row, lrow| {
        let mut st = Stats::default();
        if stop() {
            return st;
        }
        let cast = cast[y as usize].clone();
        for x in cast.clone() {
            let c = pixel(x, y, first, &mut st, true);
            put(row, lrow, x as usize, c);
        }
        // The pixels no ray is cast for: the background's pixel, copied
        // (their radiance only where it is kept for the file: adaptive
        // anti-aliasing knows them by their columns and never reads it,
        // so that its pages are never touched).
        for x in (0..cast.start).chain(cast.end..s.width) {
            let k = 3 * x as usize..3 * x as usize + 3;
            row[k.clone()].copy_from_slice(&culled_rgb);
            if s.radiance {
                lrow[k].copy_from_slice(&culled_lin);
            }
        }
        let culled = (s.width - cast.len() as u32) as u64;
        st.screen_culled += culled_st.screen_culled * culled;
        st.nonfinite_samples += culled_st.nonfinite_samples * culled;
        st.pixels += s.width as u64;
        progress(Progress::Done(s.width as u64 * first as u64));
        st
    });
    if stop() {
        return None;
    }
    let mut refined = 0;
    if let Some(a) = s.adaptive {
        (hooks.first_pass)(&rgb);
        let h = s.height as usize;
        let corner = |x: u32, y: u32, st: &mut Stats| {
            sample(x as f64, y as f64, st, true).map(|(c, _)| adaptive::shown(c))
        };
        let centres = adaptive::FirstPass {
            lin: &lin,
            w,
            h,
            cast: &cast,
            background: culled_lin,
        };
        let (again, st) = adaptive::crossed(&centres, a.threshold, corner, progress);
        stats.add(&st);
        refined = again.iter().map(Vec::len).sum::<usize>() as u64;
        if refined > 0 {
            progress(Progress::Planned(refined * s.spp as u64));
            stats.add(&rows(&mut rgb, &mut lin, w, |y, row, lrow| {
                let mut st = Stats::default();
                if stop() {
                    return st;
                }
                let xs = &again[y as usize];
                for &x in xs {
                    let c = pixel(x, y, s.spp, &mut st, true);
                    put(row, lrow, x as usize, c);
                }
                progress(Progress::Done(xs.len() as u64 * s.spp as u64));
                st
            }));
        }
        if !s.radiance {
            lin = Vec::new();
        }
    }
    if stop() {
        return None;
    }
    stats.approximated_nodes = scene.approximations.len() as u64;
    Some(Rendered {
        width: s.width,
        height: s.height,
        rgb,
        radiance: lin,
        refined,
        stats,
    })
}

/// Runs `f(y, bytes, radiance)` on every row in parallel (`radiance`
/// empty when none is kept) and sums the counters.
fn rows(
    rgb: &mut [u8],
    lin: &mut [f32],
    w: usize,
    f: impl Fn(u32, &mut [u8], &mut [f32]) -> Stats + Sync,
) -> Stats {
    let reduce = |mut a: Stats, b: Stats| {
        a.add(&b);
        a
    };
    // A row a task: rayon otherwise splits the rows into about four
    // pieces a thread and splits further only what another thread steals,
    // so on two threads a picture whose work lies in a band (a turned
    // part in the middle) left one thread idle for most of the render
    // (a speed-up of 1.25 on two threads, 3.6 on four, measured).
    // Each row's rays share what they learn (`coherent`), in their order.
    let row_task = |y: usize, row: &mut [u8], lrow: &mut [f32]| coherent(|| f(y as u32, row, lrow));
    if lin.is_empty() {
        rgb.par_chunks_mut(3 * w)
            .enumerate()
            .with_max_len(1)
            .map(|(y, row)| row_task(y, row, &mut []))
            .reduce(Stats::default, reduce)
    } else {
        rgb.par_chunks_mut(3 * w)
            .zip(lin.par_chunks_mut(3 * w))
            .enumerate()
            .with_max_len(1)
            .map(|(y, (row, lrow))| row_task(y, row, lrow))
            .reduce(Stats::default, reduce)
    }
}

/// Pixel `x` of a row: the sRGB bytes of linear colour `c`, and radiance
/// `r` if the row keeps it.
fn put(row: &mut [u8], lrow: &mut [f32], x: usize, (c, r): (DVec3, DVec3)) {
    let byte = |v: f64| {
        if crate::mutant::active("srgb_skipped") {
            (v.clamp(0.0, 1.0) * 255.0).round() as u8
        } else {
            srgb::byte(v)
        }
    };
    row[3 * x..3 * x + 3].copy_from_slice(&[byte(c.x), byte(c.y), byte(c.z)]);
    if !lrow.is_empty() {
        lrow[3 * x..3 * x + 3].copy_from_slice(&[r.x as f32, r.y as f32, r.z as f32]);
    }
}

/// 255 where the ray through the pixel centre hits the scene, else 0.
pub fn mask(scene: &Scene, s: &Settings) -> Vec<u8> {
    let cam = Camera::new(&scene.view(s.width, s.height), s.width, s.height);
    (0..s.height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let mut st = Stats::default();
            (0..s.width)
                .map(|x| {
                    let ray = cam.ray(x as f64 + 0.5, y as f64 + 0.5);
                    let hit = scene.csg.first_boundary(&ray, 0.0, f64::INFINITY, &mut st);
                    if hit.is_some() {
                        255
                    } else {
                        0
                    }
                })
                .collect::<Vec<u8>>()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A render nothing stops is `render`'s picture, and its first pass is
    /// shown before the second; one stopped after some rows is `None`,
    /// and rows asked after the stop are not begun.
    #[test]
    fn a_render_is_stopped_at_a_row_and_otherwise_the_same() {
        let src = crate::Source::new(
            "t.csg",
            "difference() { cube(10, center = true); sphere(6.5); }".to_string(),
        );
        let ast = crate::syntax::parse_csg(&src).unwrap();
        let scene = crate::scene::resolve_with(&src, &ast, Default::default()).unwrap();
        let s = Settings {
            width: 64,
            height: 48,
            spp: ADAPTIVE_SPP,
            adaptive: Some(Adaptive {
                threshold: ADAPTIVE_THRESHOLD,
            }),
            ..Settings::default()
        };
        let want = render(&scene, &s, &|_| {});
        let first = std::sync::Mutex::new(Vec::new());
        let hooks = Hooks {
            progress: &|_| {},
            stop: &|| false,
            first_pass: &|rgb| *first.lock().unwrap() = rgb.to_vec(),
        };
        let got = render_with(&scene, &s, &hooks).expect("not stopped");
        assert!(got.rgb == want.rgb && got.stats == want.stats);
        let first = first.into_inner().unwrap();
        assert_eq!(first.len(), want.rgb.len());
        assert!(first != want.rgb, "the first pass is before anti-aliasing");
        let asked = std::sync::atomic::AtomicU32::new(0);
        let rows_done = std::sync::atomic::AtomicU32::new(0);
        let stop = || asked.fetch_add(1, std::sync::atomic::Ordering::SeqCst) >= 10;
        let progress = |p: Progress| {
            if let Progress::Done(_) = p {
                rows_done.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
            }
        };
        let hooks = Hooks {
            progress: &progress,
            stop: &stop,
            first_pass: &|_| panic!("no first pass once stopped"),
        };
        assert!(render_with(&scene, &s, &hooks).is_none());
        assert!(rows_done.into_inner() <= 10, "rows begun after the stop");
    }

    #[test]
    fn both_finite_is_every_component_finite() {
        let vals = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            f64::MIN_POSITIVE / 8.0,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        // Every value in every one of the six places, the other five
        // finite (the list's first six, by a rotating index).
        for (i, &v) in vals.iter().enumerate() {
            for place in 0..6 {
                let mut c = [0.0; 6];
                for (k, x) in c.iter_mut().enumerate() {
                    *x = if k == place { v } else { vals[(i + 3 * k) % 6] };
                }
                let (a, b) = (DVec3::from_slice(&c[..3]), DVec3::from_slice(&c[3..]));
                assert_eq!(both_finite(a, b), a.is_finite() && b.is_finite(), "{c:?}");
            }
        }
    }
}
