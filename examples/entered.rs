//! Primitive tests per primary ray against the primitives the ray actually
//! enters, for issue 6's target "within 3×".
//!
//! For the ray through every `--step`-th pixel centre it counts the
//! primitive tests of the first-hit query (the work the renderer does) and,
//! by brute force over every primitive, how many solids the ray enters at
//! t > 0 (the work no renderer can avoid, if it had to find each). Prints
//! one JSON object. `tools/bench.py` runs it for the table.
//!
//! Usage: cargo run --release --example entered -- SCENE [WxH] [STEP]

use csgrt::geometry::Probe;
use csgrt::render::camera::Camera;
use csgrt::stats::Stats;
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        eprintln!("usage: entered SCENE [WxH] [STEP]");
        std::process::exit(2);
    };
    let (w, h) = args
        .get(2)
        .and_then(|s| s.split_once('x'))
        .map(|(a, b)| (a.parse().unwrap(), b.parse().unwrap()))
        .unwrap_or((640u32, 480u32));
    let step: u32 = args.get(3).map_or(4, |s| s.parse().unwrap());
    let scene = match csgrt::load(Path::new(path)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let cam = Camera::new(&scene.view(w, h), w, h);
    let (mut rays, mut tests, mut entered, mut within) = (0u64, 0u64, 0u64, 0u64);
    for y in (0..h).step_by(step as usize) {
        for x in (0..w).step_by(step as usize) {
            let ray = cam.ray(x as f64 + 0.5, y as f64 + 0.5);
            let mut st = Stats::default();
            scene.csg.first_boundary(&ray, 0.0, f64::INFINITY, &mut st);
            let n = scene
                .csg
                .prims
                .iter()
                .filter(|p| {
                    let (o, d) = p.xf.ray_to_object(&ray);
                    let mut any = false;
                    let mut q = Probe {
                        o,
                        d,
                        tmin: 0.0,
                        tmax: f64::INFINITY,
                        st: &mut Stats::default(),
                        need: csgrt::geometry::Need::Spans,
                    };
                    p.shape.spans(&mut q, &mut |(_, _, t1, _)| any |= t1 > 0.0);
                    any
                })
                .count() as u64;
            rays += 1;
            tests += st.primitive_tests;
            entered += n;
            // A ray that enters nothing may still test one primitive.
            within += u64::from(st.primitive_tests <= 3 * n.max(1));
        }
    }
    println!(
        "{{\"rays\": {rays}, \"primitive_tests\": {tests}, \"primitives_entered\": {entered}, \"tests_per_entered\": {:.3}, \"rays_within_3x\": {:.4}}}",
        tests as f64 / entered.max(1) as f64,
        within as f64 / rays as f64
    );
}
