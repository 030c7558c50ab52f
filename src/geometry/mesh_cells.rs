//! A closed triangle mesh that is not convex, cut exactly into convex
//! polytopes: the cells of a solid binary space partition by the planes of
//! its own faces (Naylor's construction). Each step takes the plane of one
//! face, drops the faces in that plane, cuts the faces that cross it in
//! two and the cell with them; a side with no face left is wholly outside
//! (in front, where the outward normals point) or wholly inside (behind).
//! The cells inside are convex and together make the solid, with nothing
//! moved: a hull, a Minkowski sum or a shadow of a non-convex polyhedron
//! then takes them as it takes any convex pieces.

use super::polytope::{box_polytope, side, signed_volume, Polytope};
use super::Aabb;
use glam::DVec3;

/// The most cells inside a mesh is cut into.
pub const MAX_MESH_CELLS: usize = 100_000;

/// One step of the partition still to do: a cell and the pieces of faces
/// in it (each a convex polygon, counter-clockwise seen from outside).
struct Step {
    cell: Polytope,
    faces: Vec<Vec<DVec3>>,
}

/// The mesh with corners `w` (placed) and triangles `tris` as convex cells
/// inside it, planes `tol` thick; `None` when it is not closed (the cells'
/// volume is not its own) or needs more than `most` cells (at most
/// [`MAX_MESH_CELLS`]).
pub fn mesh_cells(w: &[DVec3], tris: &[[u32; 3]], tol: f64, most: usize) -> Option<Vec<Polytope>> {
    let most = most.min(MAX_MESH_CELLS);
    // Its signed volume: below 0, its triangles are turned inward
    // (OpenSCAD's own order), and are taken the other way round.
    let own = signed_volume(w, tris);
    let faces: Vec<Vec<DVec3>> = tris
        .iter()
        .map(|t| {
            let mut f: Vec<DVec3> = t.iter().map(|&i| w[i as usize]).collect();
            if own < 0.0 {
                f.reverse();
            }
            f
        })
        .filter(|f| face_normal(f).is_some())
        .collect();
    let bounds = faces
        .iter()
        .flatten()
        .fold(Aabb::EMPTY, |b, &p| b.include(p));
    if faces.is_empty() || !bounds.is_bounded() {
        return None;
    }
    // Faces taken in a scattered order: neighbours in the file are often
    // neighbours in space, and one plane after another of a strip cuts few
    // faces but balances nothing.
    let mut faces = scattered(faces);
    faces.reverse();
    let mut todo = vec![Step {
        // Its own box: each side a plane of its faces, which then leave
        // it whole (within tol) rather than cut a sliver off.
        cell: box_polytope(bounds.min, bounds.max, tol)?,
        faces,
    }];
    let mut inside = Vec::new();
    while let Some(Step { cell, mut faces }) = todo.pop() {
        let Some(split) = faces.pop() else {
            continue;
        };
        let n = face_normal(&split)?;
        let d = n.dot(split[0]);
        let (mut front, mut back) = (Vec::new(), Vec::new());
        for f in faces {
            let s: Vec<f64> = f.iter().map(|&p| side(n, d, tol, p)).collect();
            if s.iter().all(|&x| x == 0.0) {
                continue;
            }
            if s.iter().all(|&x| x <= 0.0) {
                back.push(f);
            } else if s.iter().all(|&x| x >= 0.0) {
                front.push(f);
            } else {
                let (a, b) = split_polygon(&f, &s);
                front.push(a);
                back.push(b);
            }
        }
        if !front.is_empty() {
            if let Some(c) = cell.clip(-n, -d, tol) {
                todo.push(Step {
                    cell: c,
                    faces: front,
                });
            }
        }
        if let Some(c) = cell.clip(n, d, tol) {
            if back.is_empty() {
                inside.push(c);
                if inside.len() > most {
                    return None;
                }
            } else {
                todo.push(Step {
                    cell: c,
                    faces: back,
                });
            }
        }
    }
    // Closed and consistently turned: the cells fill its volume.
    let got: f64 = inside.iter().map(Polytope::volume).sum();
    let size = (bounds.max - bounds.min).max_element();
    ((got - own.abs()).abs() <= 1e-6 * size * size * size + tol * size * size).then_some(inside)
}

/// The unit normal of a polygon by Newell's formula, `None` when it has no
/// area.
fn face_normal(f: &[DVec3]) -> Option<DVec3> {
    let mut n = DVec3::ZERO;
    for i in 0..f.len() {
        let (a, b) = (f[i], f[(i + 1) % f.len()]);
        n += (a - f[0]).cross(b - f[0]);
    }
    n.try_normalize()
}

/// A convex polygon whose corners lie on both sides (`s` their sides) cut
/// in two: (in front, behind).
fn split_polygon(f: &[DVec3], s: &[f64]) -> (Vec<DVec3>, Vec<DVec3>) {
    let (mut front, mut back) = (Vec::new(), Vec::new());
    for i in 0..f.len() {
        let j = (i + 1) % f.len();
        let (p, q, sp, sq) = (f[i], f[j], s[i], s[j]);
        if sp >= 0.0 {
            front.push(p);
        }
        if sp <= 0.0 {
            back.push(p);
        }
        if (sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0) {
            let x = p + (q - p) * (sp / (sp - sq));
            front.push(x);
            back.push(x);
        }
    }
    (front, back)
}

/// The faces in the order of a stride coprime with their count (a fixed,
/// thread-free order: the same cells every run).
fn scattered(faces: Vec<Vec<DVec3>>) -> Vec<Vec<DVec3>> {
    let n = faces.len();
    let mut stride = (n as f64 * 0.618_033_988_75) as usize | 1;
    while gcd(stride, n) != 1 {
        stride += 2;
    }
    let mut slots: Vec<Option<Vec<DVec3>>> = faces.into_iter().map(Some).collect();
    (0..n)
        .map(|k| slots[(k * stride) % n].take().expect("a permutation"))
        .collect()
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}
