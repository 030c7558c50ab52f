//! Meshes as exact leaves: spans against closed forms, and the watertight
//! test's promise — a line through a shared edge or vertex of a closed
//! mesh crosses it exactly once each way.

use crate::common;
use crate::common::Rng;
use csgrt::geometry::mesh::{Mesh, MeshData};
use csgrt::geometry::{Probe, Solid};
use csgrt::stats::Stats;
use glam::DVec3;
use std::sync::Arc;

fn mesh(verts: &[[f64; 3]], tris: &[[u32; 3]]) -> Mesh {
    let v = verts.iter().map(|p| DVec3::from_array(*p)).collect();
    Mesh {
        data: Arc::new(MeshData::new(v, tris.to_vec())),
    }
}

/// The unit cube [0, 1]³ as 12 triangles, wound outward.
fn cube() -> Mesh {
    let v: Vec<[f64; 3]> = (0..8)
        .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let tris: Vec<[u32; 3]> = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    mesh(&v, &tris)
}

/// The unit cube with each face an n×n grid of squares, two triangles
/// each: more triangles than a mesh is clipped by planes for
/// (`PLANES_MAX_TRIANGLES`), so lines cross its triangles one by one.
fn fine_cube(n: u32) -> Mesh {
    let mut index = std::collections::HashMap::new();
    let mut v: Vec<[f64; 3]> = Vec::new();
    let mut at = |p: [u32; 3]| {
        *index.entry(p).or_insert_with(|| {
            v.push(p.map(|c| c as f64 / n as f64));
            v.len() as u32 - 1
        })
    };
    let mut tris = Vec::new();
    for axis in 0..3 {
        for side in [0, n] {
            for i in 0..n {
                for j in 0..n {
                    let mut p = |a: u32, b: u32| {
                        let mut c = [0; 3];
                        c[axis] = side;
                        c[(axis + 1) % 3] = a;
                        c[(axis + 2) % 3] = b;
                        at(c)
                    };
                    let q = [p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)];
                    tris.push([q[0], q[1], q[2]]);
                    tris.push([q[0], q[2], q[3]]);
                }
            }
        }
    }
    assert!(tris.len() > csgrt::geometry::mesh::PLANES_MAX_TRIANGLES);
    mesh(&v, &tris)
}

/// Every span of the whole line, with the parts of its ends.
fn raw_spans(m: &Mesh, o: DVec3, d: DVec3) -> Vec<csgrt::geometry::solid::RawSpan> {
    let mut st = Stats::default();
    let mut out = Vec::new();
    let mut q = Probe {
        o,
        d,
        tmin: f64::NEG_INFINITY,
        tmax: f64::INFINITY,
        st: &mut st,
        need: csgrt::geometry::Need::Spans,
    };
    m.spans(&mut q, &mut |s| out.push(s));
    out
}

fn spans(m: &Mesh, o: DVec3, d: DVec3) -> Vec<(f64, f64)> {
    raw_spans(m, o, d).iter().map(|s| (s.0, s.2)).collect()
}

/// The closed form: the slab test of [0, 1]³.
fn slab(o: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k] < 0.0 || o[k] > 1.0 {
                return None;
            }
            continue;
        }
        let (a, b) = ((0.0 - o[k]) / d[k], (1.0 - o[k]) / d[k]);
        lo = lo.max(a.min(b));
        hi = hi.min(a.max(b));
    }
    (lo < hi).then_some((lo, hi))
}

#[test]
fn a_cube_mesh_has_the_spans_of_the_cube() {
    // Clipped by its planes (12 triangles) and crossed triangle by
    // triangle (the fine cube).
    for m in [cube(), fine_cube(3)] {
        cube_spans(&m);
    }
}

fn cube_spans(m: &Mesh) {
    let mut rng = Rng(11);
    let mut met = 0;
    for _ in 0..2000 {
        let o = DVec3::new(
            rng.range(-2.0, 3.0),
            rng.range(-2.0, 3.0),
            rng.range(-2.0, 3.0),
        );
        let at = DVec3::new(
            rng.range(-0.2, 1.2),
            rng.range(-0.2, 1.2),
            rng.range(-0.2, 1.2),
        );
        let d = (at - o).normalize();
        let got = spans(m, o, d);
        match slab(o, d) {
            None => assert!(got.is_empty(), "{o} {d}: {got:?}"),
            Some((lo, hi)) => {
                met += 1;
                assert_eq!(got.len(), 1, "{o} {d}: {got:?} want {lo} {hi}");
                assert!(
                    (got[0].0 - lo).abs() < 1e-12 && (got[0].1 - hi).abs() < 1e-12,
                    "{o} {d}: {got:?} want {lo} {hi}"
                );
            }
        }
    }
    assert!(met > 1000, "{met}");
}

#[test]
fn lines_through_shared_edges_and_vertices_cross_exactly_once_each_way() {
    // Aimed exactly at the cube mesh's corners, its edges, and the
    // diagonals its faces are cut along (each shared by two triangles),
    // from outside and on into the inside: one span, the cube's. The fine
    // cube's triangles share those lines too (its squares are cut along
    // the same diagonals), and are crossed one by one.
    for m in [cube(), fine_cube(3)] {
        through_edges(&m);
    }
}

fn through_edges(m: &Mesh) {
    let mut rng = Rng(5);
    let mut aims = Vec::new();
    for i in 0..8 {
        aims.push(DVec3::new(
            (i & 1) as f64,
            ((i >> 1) & 1) as f64,
            ((i >> 2) & 1) as f64,
        ));
    }
    for _ in 0..200 {
        let s = rng.range(0.0, 1.0);
        // Edges of the cube, and the cut diagonals of x = 0 and z = 1.
        aims.push(DVec3::new(s, 0.0, 0.0));
        aims.push(DVec3::new(1.0, s, 1.0));
        aims.push(DVec3::new(0.0, s, s));
        aims.push(DVec3::new(s, s, 1.0));
    }
    let mut checked = 0;
    for (k, aim) in aims.iter().enumerate() {
        // From outside the cube, through the aim, into the inside.
        let inner = DVec3::new(
            rng.range(0.2, 0.8),
            rng.range(0.2, 0.8),
            rng.range(0.2, 0.8),
        );
        let d = (inner - *aim).normalize();
        let o = *aim - d * rng.range(1.0, 5.0);
        let got = spans(m, o, d);
        let want = slab(o, d).expect("the line goes through the inside");
        assert_eq!(got.len(), 1, "aim {k} {aim}: {got:?} want {want:?}");
        assert!(
            (got[0].0 - want.0).abs() < 1e-12 && (got[0].1 - want.1).abs() < 1e-12,
            "aim {k} {aim}: {got:?} want {want:?}"
        );
        checked += 1;
    }
    assert_eq!(checked, 808);
}

#[test]
fn a_mesh_wound_either_way_or_both_is_the_same_solid() {
    // Parity needs no orientation: the cube with every triangle reversed,
    // and with every other one reversed, has the same spans and outward
    // normals; clipped by planes (12 triangles) and crossed one by one
    // (the fine cube).
    for base in [cube(), fine_cube(3)] {
        wound(&base);
    }
}

fn wound(base: &Mesh) {
    let flip = |keep: &dyn Fn(usize) -> bool| {
        let d = &base.data;
        let tris: Vec<[u32; 3]> = d
            .tris
            .iter()
            .enumerate()
            .map(|(i, t)| if keep(i) { *t } else { [t[0], t[2], t[1]] })
            .collect();
        Mesh {
            data: Arc::new(MeshData::new(d.verts.clone(), tris)),
        }
    };
    let reversed = flip(&|_| false);
    let mixed = flip(&|i| i % 2 == 0);
    let mut rng = Rng(9);
    for _ in 0..500 {
        let o = DVec3::new(
            rng.range(-2.0, 3.0),
            rng.range(-2.0, 3.0),
            rng.range(-2.0, 3.0),
        );
        let at = DVec3::new(
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        );
        let d = (at - o).normalize();
        for m in [&reversed, &mixed] {
            let got = raw_spans(m, o, d);
            assert_eq!(got.len(), 1);
            let (t0, p0, t1, p1) = got[0];
            let want = slab(o, d).unwrap();
            assert!((t0 - want.0).abs() < 1e-12 && (t1 - want.1).abs() < 1e-12);
            // Outward: against the line where it enters, along it where it
            // leaves.
            assert!(m.normal(o + t0 * d, p0).dot(d) < 0.0);
            assert!(m.normal(o + t1 * d, p1).dot(d) > 0.0);
        }
    }
}

#[test]
fn an_open_mesh_is_closed_by_parity() {
    // The cube without its top: a line in through the open top crosses
    // once, so the solid runs on past the bottom; the resolver warns.
    let m = cube();
    let d = &m.data;
    let tris: Vec<[u32; 3]> = d
        .tris
        .iter()
        .copied()
        .filter(|t| !t.iter().all(|&i| d.verts[i as usize].z == 1.0))
        .collect();
    assert_eq!(tris.len(), 10);
    let (open, many) = csgrt::geometry::mesh::edge_use(&tris);
    assert_eq!((open, many), (4, 0));
}

#[test]
fn lines_along_a_face_or_an_edge_never_leave_a_span_open() {
    // Axis-aligned lines exactly in the cube's face planes and along its
    // edges: the edge functions are exactly zero, and the ownership rule
    // must count the way in and the way out alike — the span is the
    // cube's, or (grazing) nothing, never one that runs on to infinity.
    // The cube of 12 triangles is clipped by its faces' planes (a line in
    // one is outside); the fine cube's triangles are crossed one by one.
    for (m, least) in [(cube(), 100), (fine_cube(4), 500)] {
        lines_along_faces(&m, least);
    }
}

fn lines_along_faces(m: &Mesh, least: usize) {
    let mut rng = Rng(3);
    let mut seen = 0;
    for _ in 0..300 {
        let s = rng.range(0.0, 1.0);
        let u = [0.0, 1.0, s][rng.range(0.0, 3.0) as usize];
        let v = [0.0, 1.0, s][rng.range(0.0, 3.0) as usize];
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let mut o = DVec3::ZERO;
                o[(axis + 1) % 3] = u;
                o[(axis + 2) % 3] = v;
                o[axis] = -2.0 * sign + 0.5;
                let mut d = DVec3::ZERO;
                d[axis] = sign;
                let got = spans(m, o, d);
                assert!(got.iter().all(|s| s.1.is_finite()), "{o} {d}: {got:?}");
                if let Some(s) = got.first() {
                    let want = slab(o, d).unwrap();
                    assert_eq!(got.len(), 1);
                    assert!((s.0 - want.0).abs() < 1e-12 && (s.1 - want.1).abs() < 1e-12);
                    seen += 1;
                }
            }
        }
    }
    assert!(seen > least, "{seen}");
}

/// Runs `import("NAME")` of a file holding `bytes`; (status, stderr, the
/// files left in the folder).
fn import_run(name: &str, bytes: &[u8]) -> (i32, String, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(name), bytes).unwrap();
    let scene = format!("import(file = \"{name}\", convexity = 1);\n");
    std::fs::write(dir.path().join("x.csg"), &scene).unwrap();
    let r = common::csgrt(dir.path(), &["x.csg", "-q", "--strict"]);
    (r.status, r.stderr, common::files(dir.path()))
}

#[test]
fn a_bad_mesh_file_is_a_warning_at_the_import_naming_the_file_and_line() {
    let caret = "  |\n1 | import(file = \"F\", convexity = 1);\n  |               ^^^^^^^";
    let cases: [(&str, &[u8], &str); 5] = [
        (
            "a.off",
            b"OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 9\n",
            "error: `a.off`, line 7: point index 9 is out of range: expected 0 to 3",
        ),
        (
            "b.off",
            b"OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n",
            "error: `b.off`, line 4: expected a coordinate, found `x`",
        ),
        (
            "c.stl",
            b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\n",
            "error: `c.stl`, line 5: `zero` is not a number",
        ),
        (
            "d.stl",
            b"not an stl",
            "error: `d.stl`: neither a binary STL (84 + 50·n bytes) nor an ASCII one (beginning with `solid`)",
        ),
        (
            "e.off",
            b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            "error: `e.off`, line 6: a face of 2 points: expected 3 or more",
        ),
    ];
    for (name, bytes, first) in cases {
        let (status, stderr, files) = import_run(name, bytes);
        assert_eq!(status, 2, "{name}: {stderr}");
        let ext = name.rsplit('.').next().unwrap();
        let want = format!(
            "{first}\n --> x.csg:1:15\n{} expected a .{ext} mesh; this `import` is left out, as OpenSCAD leaves it out (an error under --strict)\n",
            caret.replace('F', name)
        );
        assert_eq!(stderr, want, "{name}");
        assert_eq!(files.len(), 2, "{name}: no output, {files:?}");
    }
    // A missing file: the same place, the system's reason.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("x.csg"), "import(\"gone.stl\");\n").unwrap();
    let r = common::csgrt(dir.path(), &["x.csg", "-q", "--strict"]);
    assert_eq!(r.status, 2);
    assert!(
        r.stderr.starts_with("error: cannot read mesh `gone.stl`: "),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("x.csg:1:8"), "{}", r.stderr);
}

#[test]
fn stl_binary_and_ascii_of_the_same_triangles_are_the_same_mesh() {
    // A tetrahedron written both ways, with coordinates f32 holds exactly.
    let tris = [
        [[0.0f32, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.5]],
        [[0.0, 0.0, 0.0], [0.0, 0.0, 1.5], [0.0, 1.0, 0.0]],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.5]],
    ];
    let mut bin = vec![0u8; 80];
    bin.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    let mut ascii = String::from("solid t\n");
    for t in &tris {
        bin.extend_from_slice(&[0u8; 12]);
        ascii += " facet normal 0 0 0\n  outer loop\n";
        for v in t {
            for c in v {
                bin.extend_from_slice(&c.to_le_bytes());
            }
            ascii += &format!("   vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        bin.extend_from_slice(&[0, 0]);
        ascii += "  endloop\n endfacet\n";
    }
    ascii += "endsolid t\n";
    let a = csgrt::import::meshfile::read("stl", &bin).unwrap();
    let b = csgrt::import::meshfile::read("stl", ascii.as_bytes()).unwrap();
    assert_eq!(a.points, b.points);
    assert_eq!(a.faces, b.faces);
    // Shared corners are merged: 4 points, each face three of them.
    assert_eq!(a.points.len(), 4);
    assert_eq!(a.faces.len(), 4);
}

#[test]
fn obj_and_3mf_bring_the_points_and_faces_they_list() {
    // The same tetrahedron (corners 0 and 10 on each axis) as OBJ text
    // (1-based indices, one face a quad split later) and as a 3MF package.
    let obj = b"v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let a = csgrt::import::meshfile::read("obj", obj).unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmf = std::fs::read(root.join("tests/openscad/meshes/tetra.3mf")).unwrap();
    let b = csgrt::import::meshfile::read("3mf", &tmf).unwrap();
    let corners = [
        [0.0, 0.0, 0.0],
        [10.0, 0.0, 0.0],
        [0.0, 10.0, 0.0],
        [0.0, 0.0, 10.0],
    ];
    let want = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]].map(|f| f.map(|i| corners[i]));
    for m in [&a, &b] {
        // The faces' corners, in order (a reader may number points its own
        // way: tobj by first use).
        let faces: Vec<[[f64; 3]; 3]> = m
            .faces
            .iter()
            .map(|f| [0, 1, 2].map(|k| m.points[f[k] as usize].to_array()))
            .collect();
        assert_eq!(faces, want);
        assert_eq!(m.points.len(), 4);
    }
}
