//! `--trace-rays`: first-surface queries for arbitrary rays.
//!
//! Input: one ray a line, `ox oy oz dx dy dz`; blank lines and `#` comments
//! are skipped. Output, a line per ray: `t nx ny nz` — the distance along
//! the normalised direction to the first surface with t > 0 and the unit
//! outward normal there, each printed as the shortest decimal that reads
//! back to the same f64 — or `miss`.

use crate::csg::SurfaceHit;
use crate::error::{Result, TextRange};
use crate::geometry::Ray;
use crate::scene::Scene;
use crate::source::Source;
use crate::stats::Stats;
use glam::DVec3;
use std::fmt::Write as _;

/// Parses every ray first, so a bad line produces no output at all.
pub fn parse_rays(src: &Source) -> Result<Vec<Ray>> {
    let mut rays = Vec::new();
    let mut offset = 0;
    for line in src.text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let body = line.split('#').next().unwrap_or("");
        let mut nums = Vec::with_capacity(6);
        let mut pos = start;
        for word in body.split_ascii_whitespace() {
            let at = start + body[pos - start..].find(word).unwrap() + (pos - start);
            pos = at + word.len();
            let span = TextRange::new(at, pos);
            match word.parse::<f64>() {
                Ok(x) if x.is_finite() => nums.push((x, span)),
                _ => {
                    return Err(src.error(
                        span,
                        format!("`{word}` is not a finite number"),
                        "expected `ox oy oz dx dy dz`",
                    ))
                }
            }
        }
        match nums.len() {
            0 => continue,
            6 => {}
            n => {
                let span = TextRange::new(start, start + line.trim_end().len());
                return Err(src.error(
                    span,
                    format!("a ray needs 6 numbers, this line has {n}"),
                    "expected `ox oy oz dx dy dz`",
                ));
            }
        }
        let v = |i: usize| DVec3::new(nums[i].0, nums[i + 1].0, nums[i + 2].0);
        let dir = v(3);
        if dir.length_squared() == 0.0 || !dir.length_squared().is_finite() {
            let span = TextRange::new(nums[3].1.start, nums[5].1.end);
            return Err(src.error(
                span,
                "a ray's direction must not be zero",
                "expected a non-zero direction",
            ));
        }
        rays.push(Ray::new(v(0), dir.normalize()));
    }
    Ok(rays)
}

/// The first hit of one ray.
pub fn trace(scene: &Scene, ray: &Ray, st: &mut Stats) -> Option<SurfaceHit> {
    scene.csg.first_hit(ray, 0.0, f64::INFINITY, st)
}

/// The output line for one ray's first hit: `miss`, or its distance and
/// normal.
pub fn line(hit: Option<&SurfaceHit>) -> String {
    match hit {
        None => "miss".to_string(),
        Some(h) => {
            let mut s = String::new();
            let n = if crate::mutant::active("normals_inward") {
                -h.normal
            } else {
                h.normal
            };
            write!(s, "{} {} {} {}", h.t, n.x, n.y, n.z).unwrap();
            s
        }
    }
}
