//! Every sample a render at WxH may trace — each pixel's centre and the
//! samples adaptive anti-aliasing adds (`ADAPTIVE_SPP`) — with its primary
//! hit (primitive, t) and, for each directional light the surface faces,
//! the shadow ray and whether it is blocked (`-` where the surface faces
//! away). One line a sample that hits. Two builds' outputs side by side
//! show which shadow decisions a change of a solid's arithmetic moves;
//! `tools/explain_shadows.py` settles each one by exact arithmetic (for
//! scenes of tori).
//!
//! Usage: cargo run --release --example samples -- SCENE [WxH] > out.txt

use csgrt::geometry::Ray;
use csgrt::math::robust::{offset_origin, point_error};
use csgrt::render::camera::Camera;
use csgrt::render::sampler;
use csgrt::stats::Stats;
use std::io::Write;
use std::path::Path;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let scene = csgrt::load(Path::new(&a[1])).unwrap();
    let (w, h) = a
        .get(2)
        .and_then(|s| s.split_once('x'))
        .map(|(a, b)| (a.parse().unwrap(), b.parse().unwrap()))
        .unwrap_or((640u32, 480u32));
    let cam = Camera::new(&scene.view(w, h), w, h);
    let mut st = Stats::default();
    let out = std::io::stdout();
    let mut out = std::io::BufWriter::new(out.lock());
    for y in 0..h {
        for x in 0..w {
            let n = csgrt::render::ADAPTIVE_SPP;
            let centre = std::iter::once((0.5, 0.5));
            for (s, (ox, oy)) in sampler::offsets(x, y, n).chain(centre).enumerate() {
                let ray = cam.ray(x as f64 + ox, y as f64 + oy);
                let Some(hit) = scene.csg.first_hit(&ray, 0.0, f64::INFINITY, &mut st) else {
                    continue;
                };
                let err = point_error(hit.point, ray.origin, hit.t * ray.dir);
                write!(out, "{x} {y} {s} {} {:?}", hit.prim, hit.t).unwrap();
                for l in &scene.lights {
                    if let csgrt::scene::Light::Directional { direction, .. } = *l {
                        let l = -direction;
                        let n = hit.normal;
                        let ns = if n.dot(-ray.dir) < 0.0 { -n } else { n };
                        if ns.dot(l) <= 0.0 {
                            write!(out, " -").unwrap();
                            continue;
                        }
                        let sr = Ray::new(offset_origin(hit.point, n, err, l), l);
                        let occ = scene.csg.occluded(&sr, 0.0, f64::INFINITY, &mut st);
                        write!(
                            out,
                            " {} [{:?} {:?} {:?} {:?} {:?} {:?}]",
                            occ as u8,
                            sr.origin.x,
                            sr.origin.y,
                            sr.origin.z,
                            sr.dir.x,
                            sr.dir.y,
                            sr.dir.z
                        )
                        .unwrap();
                    }
                }
                writeln!(out).unwrap();
            }
        }
    }
}
