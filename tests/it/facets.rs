//! `--facets openscad` renders exactly the mesh OpenSCAD exports: csgrt's
//! faceted circles, cylinders, spheres and turned shapes against OpenSCAD 2021.01's own
//! mesh of the same file (`tests/facets/*.off`, printed to 6
//! digits), ray by ray; and the exact surfaces are told apart from it.

use crate::common::Rng;
use csgrt::geometry::Ray;
use csgrt::scene::Facets;
use csgrt::stats::Stats;
use csgrt::{load_csg, load_csg_with, Scene, Source};
use glam::DVec3;
use std::path::Path;

fn dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/facets")
}

fn scene(name: &str, facets: Facets) -> Scene {
    let path = dir().join(format!("{name}.csg"));
    let text = std::fs::read_to_string(&path).unwrap();
    load_csg_with(&Source::new(path.display().to_string(), text), facets).unwrap()
}

fn openscad_mesh(name: &str) -> Scene {
    let path = dir().join(format!("{name}_off.csg"));
    load_csg(&Source::new(
        path.display().to_string(),
        format!("import(\"{name}.off\");\n"),
    ))
    .unwrap()
}

/// A box as its ranges in x, y and z.
type Ranges = [(f64, f64); 3];

/// Where the rays of [`compare`] start and what they aim at, for each model.
fn boxes(name: &str) -> (Ranges, Ranges) {
    match name {
        "solids" => (
            [(-20.0, 45.0), (-20.0, 35.0), (10.0, 30.0)],
            [(-6.0, 27.0), (-6.0, 17.0), (-5.0, 6.0)],
        ),
        "twisted" => (
            [(-25.0, 60.0), (-25.0, 45.0), (15.0, 40.0)],
            [(-4.0, 32.0), (-4.0, 18.0), (-4.0, 9.0)],
        ),
        _ => (
            [(-25.0, 60.0), (-25.0, 45.0), (12.0, 35.0)],
            [(-9.0, 40.0), (-9.0, 25.0), (-3.0, 5.0)],
        ),
    }
}

/// Depths along the same rays: (both hit and agree to `tol` over the
/// cosine of the angle to the normal, one hits and
/// the other misses, both hit and disagree).
fn compare(name: &str, a: &Scene, b: &Scene, tol: f64) -> (usize, usize, usize) {
    let (from, to) = boxes(name);
    let mut rng = Rng(17);
    let (mut same, mut miss, mut off) = (0, 0, 0);
    let mut st = Stats::default();
    for _ in 0..4000 {
        let mut pick = |b: Ranges| {
            DVec3::new(
                rng.range(b[0].0, b[0].1),
                rng.range(b[1].0, b[1].1),
                rng.range(b[2].0, b[2].1),
            )
        };
        let o = pick(from);
        let at = pick(to);
        let ray = Ray::new(o, (at - o).normalize());
        let ha = a.csg.first_hit(&ray, 0.0, f64::INFINITY, &mut st);
        let hb = b.csg.first_hit(&ray, 0.0, f64::INFINITY, &mut st);
        match (ha, hb) {
            // A point moved by δ along the normal moves the depth by δ/|cos|.
            (Some(x), Some(y)) if (x.t - y.t).abs() * x.normal.dot(ray.dir).abs() <= tol => {
                same += 1
            }
            (Some(_), Some(_)) => off += 1,
            (None, None) => {}
            _ => miss += 1,
        }
    }
    (same, miss, off)
}

#[test]
fn openscad_facets_are_openscads_own_mesh() {
    // Circles, cylinders and spheres; rotate_extrude of circles, polygons
    // and 2-D combinations, full and part turns both ways, at x < 0 too
    // (tests/facets/turned.scad); twisted and unevenly scaled
    // linear_extrude, with and without slices, holes, centred
    // (tests/facets/twisted.scad).
    for name in ["solids", "turned", "twisted"] {
        // 6 printed digits move OpenSCAD's points by up to 5e-5 (its
        // mesh is 10⁻⁴ of the depth over the cosine off ours at most).
        let got = scene(name, Facets::OpenScad);
        let (same, miss, off) = compare(name, &got, &openscad_mesh(name), 2e-4);
        assert!(same > 1000, "{name}: {same} rays met both");
        eprintln!("{name}, openscad facets: {same} agree, {miss} hit one only, {off} disagree");
        assert!(
            miss + off == 0,
            "{name}: {miss} hit one only, {off} disagree in depth ({same} agree)"
        );
    }
}

#[test]
fn the_exact_surfaces_are_not_openscads_mesh() {
    // The check above can fail: the smooth solids differ from the mesh.
    for name in ["solids", "turned", "twisted"] {
        let got = scene(name, Facets::Exact);
        let (same, miss, off) = compare(name, &got, &openscad_mesh(name), 2e-4);
        eprintln!("{name}, exact: {same} agree, {miss} hit one only, {off} disagree");
        assert!(
            miss + off > 200,
            "{name}: {miss} hit one only, {off} disagree ({same} agree)"
        );
    }
}
