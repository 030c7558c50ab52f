//! Where a big mesh's load time goes: `cargo run --release --example
//! mesh_load -- FILE.stl` prints the seconds of each step.

use std::time::Instant;

/// The process's peak resident memory so far (Linux), in MB.
fn peak() -> String {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kb = s
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|k| k.parse::<f64>().ok())
        .unwrap_or(f64::NAN);
    format!("peak {:.0} MB", kb / 1024.0)
}

fn main() {
    let path = std::env::args().nth(1).expect("a mesh file");
    let t = Instant::now();
    let bytes = std::fs::read(&path).unwrap();
    let ext = path.rsplit('.').next().unwrap().to_ascii_lowercase();
    println!("read file   {:.3} s, {}", t.elapsed().as_secs_f64(), peak());
    let t = Instant::now();
    let m = csgrt::import::meshfile::read(&ext, &bytes).unwrap();
    println!(
        "parse+merge {:.3} s ({} points, {} faces), {}",
        t.elapsed().as_secs_f64(),
        m.points.len(),
        m.faces.len(),
        peak()
    );
    let t = Instant::now();
    let mut tris = Vec::new();
    for f in &m.faces {
        tris.extend(csgrt::geometry::triangulate::triangulate(&m.points, f));
    }
    println!("triangulate {:.3} s, {}", t.elapsed().as_secs_f64(), peak());
    drop(m.faces);
    let t = Instant::now();
    let (open, many) = csgrt::geometry::mesh::edge_use(&tris);
    println!(
        "edge use    {:.3} s ({open} open, {many} many)",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let d = csgrt::geometry::mesh::MeshData::new(m.points, tris);
    println!(
        "bvh         {:.3} s ({} triangles), {}",
        t.elapsed().as_secs_f64(),
        d.tris.len(),
        peak()
    );
}
