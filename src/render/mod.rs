//! Rendering: camera rays → CSG queries → shading → an 8-bit image.
//!
//! Rows are rendered in parallel with rayon; every pixel depends only on
//! its own coordinates, so the bytes are the same for any thread count.

pub mod camera;
pub mod probe;
pub mod sampler;
pub mod shade;

use crate::scene::Scene;
use crate::stats::Stats;
use camera::Camera;
use glam::DVec3;
use rayon::prelude::*;
use shade::Shader;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_depth: u32,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            width: 800,
            height: 600,
            spp: 1,
            max_depth: 5,
        }
    }
}

/// An 8-bit RGB image, row-major from the top left.
pub struct Rendered {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
    pub stats: Stats,
}

/// A channel value in [0, 1] as a byte: round(255·v), no gamma.
pub fn to_byte(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Renders the scene; `on_row` is called once per finished row.
pub fn render(scene: &Scene, s: &Settings, on_row: &(dyn Fn() + Sync)) -> Rendered {
    let cam = Camera::new(&scene.view(s.width, s.height), s.width, s.height);
    let shader = Shader::new(scene, s.max_depth);
    // Each row is written in place by whichever thread takes it; the
    // counters are sums and maxima, the same in any order.
    let mut rgb = vec![0u8; 3 * (s.width as usize) * (s.height as usize)];
    let stats = rgb
        .par_chunks_mut(3 * s.width as usize)
        .enumerate()
        .map(|(y, row)| {
            let y = y as u32;
            let mut st = Stats::default();
            for (x, px) in (0..s.width).zip(row.chunks_exact_mut(3)) {
                let mut sum = DVec3::ZERO;
                for k in 0..s.spp {
                    let (ox, oy) = sampler::offset(x, y, k, s.spp);
                    let ray = cam.ray(x as f64 + ox, y as f64 + oy);
                    st.primary_rays += 1;
                    let c = shader.trace(&ray, 0, 1.0, &mut st);
                    if c.is_finite() {
                        sum += c;
                    } else {
                        st.nonfinite_samples += 1;
                    }
                }
                let c = sum / s.spp as f64;
                px.copy_from_slice(&[to_byte(c.x), to_byte(c.y), to_byte(c.z)]);
                st.pixels += 1;
            }
            on_row();
            st
        })
        .reduce(Stats::default, |mut a, b| {
            a.add(&b);
            a
        });
    Rendered {
        width: s.width,
        height: s.height,
        rgb,
        stats,
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
