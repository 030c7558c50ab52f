//! A big mesh's nearest crossings alone, with no scene around them:
//! `cargo run --release --example mesh_rays -- FILE.stl RAYS.txt` prints
//! the seconds and the tests a ray (the rays as `--trace-rays` reads them).

use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("a mesh file");
    let rays = args.next().expect("a rays file");
    let bytes = std::fs::read(&path).unwrap();
    let ext = path.rsplit('.').next().unwrap().to_ascii_lowercase();
    let m = csgrt::meshfile::read(&ext, &bytes).unwrap();
    drop(bytes);
    let mut tris = Vec::new();
    for f in &m.faces {
        tris.extend(csgrt::geometry::mesh::triangulate(&m.points, f));
    }
    let d = csgrt::geometry::mesh::MeshData::new(m.points, tris);
    let text = std::fs::read_to_string(&rays).unwrap();
    let rays = csgrt::render::probe::parse_rays(&csgrt::Source::new(rays, text)).unwrap();
    let mut least = f64::INFINITY;
    for round in 0..7 {
        let mut st = csgrt::stats::Stats::default();
        let t = Instant::now();
        let mut hits = 0;
        for r in &rays {
            if d.nearest(r.origin, r.dir, 0.0, f64::INFINITY, &mut st)
                .is_some()
            {
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
