//! A big mesh's nearest crossings alone, with no scene around them:
//! `cargo run --release --example mesh_rays -- FILE.stl RAYS.txt` prints
//! the seconds and the tests a ray (the rays as `--trace-rays` reads them),
//! least of 7 rounds or of the count given third.
//! With a scene (`.csg`) instead of a mesh file it times `--trace-rays`'s
//! own query (first hit and normal) over the same rays, in rounds.

use std::time::Instant;

/// One ray's query: whether it hits.
type Query = dyn Fn(&csgrt::geometry::Ray, &mut csgrt::stats::Stats) -> bool;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("a mesh file or a scene");
    let rays = args.next().expect("a rays file");
    let rounds: usize = args
        .next()
        .map_or(7, |s| s.parse().expect("a count of rounds"));
    let text = std::fs::read_to_string(&rays).unwrap();
    let rays = csgrt::render::probe::parse_rays(&csgrt::Source::new(rays, text)).unwrap();
    let ext = path.rsplit('.').next().unwrap().to_ascii_lowercase();
    let run: Box<Query> = if ext == "csg" {
        let scene = csgrt::load(std::path::Path::new(&path)).unwrap();
        Box::new(move |r, st| csgrt::render::probe::trace(&scene, r, st).is_some())
    } else {
        let bytes = std::fs::read(&path).unwrap();
        let m = csgrt::import::meshfile::read(&ext, &bytes).unwrap();
        drop(bytes);
        let mut tris = Vec::new();
        for f in &m.faces {
            tris.extend(csgrt::geometry::triangulate::triangulate(&m.points, f));
        }
        let d = csgrt::geometry::mesh::MeshData::new(m.points, tris);
        Box::new(move |r, st| d.nearest(r.origin, r.dir, 0.0, f64::INFINITY, st).is_some())
    };
    let mut least = f64::INFINITY;
    for round in 0..rounds {
        let mut st = csgrt::stats::Stats::default();
        let t = Instant::now();
        let mut hits = 0;
        for r in &rays {
            if run(r, &mut st) {
                hits += 1;
            }
        }
        let s = t.elapsed().as_secs_f64();
        least = least.min(s);
        let n = rays.len() as f64;
        println!(
            "round {round}: {s:.3} s, {hits} hits, {:.1} boxes and {:.2} triangles a ray",
            st.bound_tests as f64 / n,
            st.triangle_tests as f64 / n
        );
    }
    println!("least {least:.3} s");
}
