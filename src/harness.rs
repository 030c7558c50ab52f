//! The fuzzing harness, shared by `fuzz/fuzz_targets/scene.rs` (libFuzzer,
//! nightly) and `tests/it/fuzz_corpus.rs` (which replays the kept corpus on
//! stable in the normal test line).

use crate::error::Error;
use crate::export::{dump, pov};
use crate::render::{self, Settings};
use crate::Source;

/// Any bytes → parse → resolve → a tiny render, the mask, the JSON dump and
/// the POV-Ray export. The first byte picks the format (odd: `.ray`, even:
/// `.csg`), the rest is the file text. Panics if anything panics, if a
/// scene error carries no place in the file, or if a render produces a
/// non-finite sample or the wrong number of bytes.
pub fn exercise(data: &[u8]) {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    // The CLI refuses text that is not UTF-8 before parsing.
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let ray = pick & 1 == 1;
    let name = if ray { "fuzz.ray" } else { "fuzz.csg" };
    let src = Source::new(name, text);
    let loaded = if ray {
        crate::load_ray(&src)
    } else {
        crate::load_csg(&src)
    };
    let scene = match loaded {
        Ok(scene) => scene,
        Err(Error::Scene(d)) => {
            let shown = d.to_string();
            let place = format!("--> {name}:{}:{}", d.line, d.col);
            assert!(shown.contains(&place), "no place in {shown}");
            return;
        }
        Err(e) => panic!("an error without a place: {e}"),
    };
    let s = Settings {
        width: 6,
        height: 4,
        spp: 2,
        max_depth: 4,
        ..Settings::default()
    };
    let out = render::render(&scene, &s, &|_| {});
    assert_eq!(out.rgb.len(), 6 * 4 * 3);
    assert_eq!(out.stats.nonfinite_samples, 0, "a non-finite sample");
    assert_eq!(render::mask(&scene, &s).len(), 6 * 4);
    let cam = scene.view(s.width, s.height);
    let _ = dump::scene_json(&scene, &cam, s.width, s.height).to_string();
    let _ = pov::scene_sdl(&scene, &cam, s.width, s.height, s.max_depth);
}

/// Any bytes as a DXF drawing (`import`), then as a font (`text`), then as
/// OpenSCAD's dependency list: an error or a drawing, a layout or the
/// fallback, a list of names, never a panic.
pub fn exercise_readers(data: &[u8]) {
    if let Ok(d) = crate::import::dxf::read(data, "", glam::DVec2::ZERO, 1.0, &|_| None) {
        assert!(d.paths.iter().all(|p| p.pts.len() == p.arcs.len()));
    }
    let _ = crate::import::text::layout_with_font_bytes(data, "AVo fi");
    // And as OpenSCAD's `-d` dependency list (`--watch` of a `.scad`).
    let deps = crate::import::scad::make_deps(&String::from_utf8_lossy(data));
    assert!(
        deps.iter().all(|p| !p.as_os_str().is_empty()),
        "an empty name"
    );
}

/// Any bytes as an SVG drawing (`fuzz/fuzz_targets/svg.rs`), imported by a
/// scene — `linear_extrude(1) import("fuzz.svg", center = …)`, the first
/// byte choosing `center` — and rendered small: an error with its place,
/// or a picture of finite samples, never a panic.
pub fn exercise_svg(data: &[u8]) {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("fuzz.svg"), rest).expect("the drawing written");
    let center = if pick & 1 == 1 { "true" } else { "false" };
    let text = format!("linear_extrude(height = 1) import(\"fuzz.svg\", center = {center});\n");
    let name = dir.path().join("fuzz.csg").to_string_lossy().into_owned();
    let src = Source::new(&name, &text);
    let scene = match crate::load_csg(&src) {
        Ok(scene) => scene,
        Err(Error::Scene(d)) => {
            let at = text.find("\"fuzz.svg\"").expect("the file argument") + 1;
            assert_eq!((d.line, d.col), (1, at), "the error is at the file: {d}");
            return;
        }
        Err(e) => panic!("an error without a place: {e}"),
    };
    let s = Settings {
        width: 6,
        height: 4,
        spp: 1,
        max_depth: 2,
        ..Settings::default()
    };
    let out = render::render(&scene, &s, &|_| {});
    assert_eq!(out.stats.nonfinite_samples, 0, "a non-finite sample");
}

/// The mesh readers' fuzz targets: (the target's and corpus's suffix, the
/// format's extension): `fuzz/fuzz_targets/mesh_DIR.rs`, `fuzz/corpus/mesh_DIR`.
pub const MESH_TARGETS: &[(&str, &str)] = &[
    ("stl", "stl"),
    ("off", "off"),
    ("obj", "obj"),
    ("threemf", "3mf"),
    ("amf", "amf"),
    ("nef3", "nef3"),
];

/// Any bytes as a mesh file of format `ext` (`fuzz/fuzz_targets/mesh_*.rs`):
/// the reader must answer a mesh or an error, never panic, and a mesh it
/// answers must be one csgrt can place and cast rays through.
pub fn exercise_mesh(ext: &str, data: &[u8]) {
    use crate::geometry::mesh::{Mesh, MeshData};
    use crate::geometry::mesh_bvh::too_far;
    use crate::geometry::triangulate::triangulate;
    use crate::geometry::{Probe, Solid};
    let Ok(m) = crate::import::meshfile::read(ext, data) else {
        return;
    };
    assert!(m.points.iter().all(|p| p.is_finite()));
    let mut tris = Vec::new();
    for f in &m.faces {
        assert!(f.len() >= 3 && f.iter().all(|&i| (i as usize) < m.points.len()));
        tris.extend(triangulate(&m.points, f));
    }
    // As the resolver: no mesh of more, or with points farther out.
    let far = too_far(&m.points).is_some();
    if tris.is_empty() || tris.len() > 100_000 || far {
        return;
    }
    let mesh = Mesh {
        data: std::sync::Arc::new(MeshData::new(m.points, tris)),
    };
    let mut st = crate::stats::Stats::default();
    for d in [glam::DVec3::X, glam::DVec3::new(0.3, -0.5, 0.8)] {
        let mut q = Probe {
            o: glam::DVec3::new(-1e3, 0.1, 0.2),
            d,
            tmin: f64::NEG_INFINITY,
            tmax: f64::INFINITY,
            st: &mut st,
            need: crate::geometry::Need::Spans,
        };
        mesh.spans(&mut q, &mut |(t0, _, t1, _)| assert!(t0 < t1));
    }
}
