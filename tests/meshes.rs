//! Meshes as exact leaves: spans against closed forms, and the watertight
//! test's promise — a line through a shared edge or vertex of a closed
//! mesh crosses it exactly once each way.

mod common;
use common::Rng;
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

fn spans(m: &Mesh, o: DVec3, d: DVec3) -> Vec<(f64, f64)> {
    let mut st = Stats::default();
    let mut out = Vec::new();
    let mut q = Probe {
        o,
        d,
        tmin: f64::NEG_INFINITY,
        tmax: f64::INFINITY,
        st: &mut st,
    };
    m.spans(&mut q, &mut |(t0, _, t1, _)| out.push((t0, t1)));
    out
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
    let m = cube();
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
        let got = spans(&m, o, d);
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
    // from outside and on into the inside: one span, the cube's.
    let m = cube();
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
        let got = spans(&m, o, d);
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
    // normals.
    let base = cube();
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
            let mut st = Stats::default();
            let mut got = Vec::new();
            let mut q = Probe {
                o,
                d,
                tmin: f64::NEG_INFINITY,
                tmax: f64::INFINITY,
                st: &mut st,
            };
            m.spans(&mut q, &mut |s| got.push(s));
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
    let m = cube();
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
                let got = spans(&m, o, d);
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
    assert!(seen > 500, "{seen}");
}
