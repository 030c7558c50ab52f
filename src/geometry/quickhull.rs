//! The convex hull of points in space: Barber, Dobkin and Huhdanpaa's
//! quickhull ("The Quickhull Algorithm for Convex Hulls", 1996). From a
//! tetrahedron of extreme points, each face keeps the points above its
//! plane; the farthest of them is added by removing the faces it sees (a
//! connected patch, found from the face that holds it) and joining it to
//! their horizon. A point within the tolerance of a plane counts as on it,
//! so near-coplanar points never make slivers; the hull is then exact to
//! that tolerance: every input point lies within it of the hull, and every
//! hull vertex is an input point.

use glam::DVec3;
use std::collections::HashMap;

/// The most points a hull is taken of.
pub const MAX_POINTS: usize = 4_000_000;

/// A face: its corners (counter-clockwise seen from outside), its unit
/// outward normal and offset, the points above it, and whether it is gone.
struct Face {
    v: [u32; 3],
    n: DVec3,
    d: f64,
    above: Vec<u32>,
    alive: bool,
}

/// The hull of `pts` as the points it uses and outward triangles over
/// them, with `tol` (absolute) as the thickness of a plane; `None` when
/// the points span no volume (all within `tol` of a plane), or past
/// [`MAX_POINTS`].
pub fn hull(pts: &[DVec3], tol: f64) -> Option<(Vec<DVec3>, Vec<[u32; 3]>)> {
    if pts.len() < 4 || pts.len() > MAX_POINTS || pts.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let start = tetrahedron(pts, tol)?;
    let mut faces: Vec<Face> = Vec::new();
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    let [a, b, c, d] = start;
    // Wound so that the fourth point is below each face.
    let below = (pts[b as usize] - pts[a as usize])
        .cross(pts[c as usize] - pts[a as usize])
        .dot(pts[d as usize] - pts[a as usize])
        < 0.0;
    let tris = if below {
        [[a, b, c], [a, d, b], [b, d, c], [c, d, a]]
    } else {
        [[a, c, b], [a, b, d], [b, c, d], [c, a, d]]
    };
    for t in tris {
        add_face(pts, &mut faces, &mut edges, t);
    }
    for i in 0..pts.len() as u32 {
        if start.contains(&i) {
            continue;
        }
        assign(pts, &mut faces, &[0, 1, 2, 3], i, tol);
    }
    let mut stack: Vec<usize> = (0..4).collect();
    while let Some(f) = stack.pop() {
        if !faces[f].alive || faces[f].above.is_empty() {
            continue;
        }
        let (n, d) = (faces[f].n, faces[f].d);
        let eye = *faces[f]
            .above
            .iter()
            .max_by(|&&x, &&y| {
                let (px, py) = (pts[x as usize], pts[y as usize]);
                (n.dot(px) - d).total_cmp(&(n.dot(py) - d))
            })
            .expect("points above");
        let p = pts[eye as usize];
        // The faces the point sees, connected to this one.
        let mut seen = vec![f];
        let mut k = 0;
        faces[f].alive = false;
        while k < seen.len() {
            let v = faces[seen[k]].v;
            for e in 0..3 {
                let (x, y) = (v[e], v[(e + 1) % 3]);
                let g = edges[&(y, x)];
                if faces[g].alive && faces[g].n.dot(p) - faces[g].d > tol {
                    faces[g].alive = false;
                    seen.push(g);
                }
            }
            k += 1;
        }
        // The horizon: edges of seen faces whose twin is still alive.
        let mut horizon = Vec::new();
        let mut orphans = Vec::new();
        for &s in &seen {
            let v = faces[s].v;
            for e in 0..3 {
                let (x, y) = (v[e], v[(e + 1) % 3]);
                if faces[edges[&(y, x)]].alive {
                    horizon.push((x, y));
                }
            }
        }
        for &s in &seen {
            let v = faces[s].v;
            for e in 0..3 {
                edges.remove(&(v[e], v[(e + 1) % 3]));
            }
            orphans.append(&mut faces[s].above);
        }
        let mut made = Vec::with_capacity(horizon.len());
        for (x, y) in horizon {
            made.push(add_face(pts, &mut faces, &mut edges, [x, y, eye]));
        }
        for o in orphans {
            if o != eye {
                assign(pts, &mut faces, &made, o, tol);
            }
        }
        stack.extend(made);
    }
    // The faces left, over the points they use.
    let mut index = vec![u32::MAX; pts.len()];
    let mut used = Vec::new();
    let mut out = Vec::new();
    for f in faces.iter().filter(|f| f.alive) {
        out.push(f.v.map(|i| {
            let k = &mut index[i as usize];
            if *k == u32::MAX {
                *k = used.len() as u32;
                used.push(pts[i as usize]);
            }
            *k
        }));
    }
    Some((used, out))
}

/// Four points spanning a volume: the extremes along an axis, the point
/// farthest from their line, then from their plane.
fn tetrahedron(pts: &[DVec3], tol: f64) -> Option<[u32; 4]> {
    let far = |f: &dyn Fn(DVec3) -> f64| -> (u32, f64) {
        let (i, v) = pts
            .iter()
            .enumerate()
            .map(|(i, &p)| (i, f(p)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .expect("points");
        (i as u32, v)
    };
    let (mut a, mut b, mut spread) = (0, 0, -1.0);
    for axis in 0..3 {
        let (lo, vlo) = far(&|p: DVec3| -p[axis]);
        let (hi, vhi) = far(&|p: DVec3| p[axis]);
        if vhi + vlo > spread {
            (a, b, spread) = (lo, hi, vhi + vlo);
        }
    }
    let (pa, pb) = (pts[a as usize], pts[b as usize]);
    let dir = (pb - pa).try_normalize()?;
    let (c, dc) = far(&|p: DVec3| (p - pa).reject_from_normalized(dir).length());
    if dc <= tol {
        return None;
    }
    let n = dir.cross(pts[c as usize] - pa).normalize();
    let (d, dd) = far(&|p: DVec3| (p - pa).dot(n).abs());
    (dd > tol).then_some([a, b, c, d])
}

/// A new face over `v`, its plane, and its edges recorded; its index.
fn add_face(
    pts: &[DVec3],
    faces: &mut Vec<Face>,
    edges: &mut HashMap<(u32, u32), usize>,
    v: [u32; 3],
) -> usize {
    let [a, b, c] = v.map(|i| pts[i as usize]);
    // The normal from the longest two edges' cross product is the same
    // plane; any two give it to rounding.
    let n = (b - a).cross(c - a).normalize_or_zero();
    let f = faces.len();
    faces.push(Face {
        v,
        n,
        d: n.dot(a),
        above: Vec::new(),
        alive: true,
    });
    for e in 0..3 {
        edges.insert((v[e], v[(e + 1) % 3]), f);
    }
    f
}

/// Point `i` given to the first of `candidates` it lies above (by more
/// than `tol`); inside them all, it is dropped.
fn assign(pts: &[DVec3], faces: &mut [Face], candidates: &[usize], i: u32, tol: f64) {
    let p = pts[i as usize];
    for &f in candidates {
        if faces[f].alive && faces[f].n.dot(p) - faces[f].d > tol {
            faces[f].above.push(i);
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (no dependency on a crate's
    /// sequence).
    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Every input point is inside or on every face (within tol), every
    /// edge has exactly one twin (closed), and Euler's V − E + F = 2.
    fn check(pts: &[DVec3], verts: &[DVec3], tris: &[[u32; 3]], tol: f64) {
        for t in tris {
            let [a, b, c] = t.map(|i| verts[i as usize]);
            let n = (b - a).cross(c - a).normalize();
            for p in pts {
                assert!(n.dot(*p - a) <= 10.0 * tol, "a point outside a face");
            }
        }
        let mut e = HashMap::new();
        for t in tris {
            for k in 0..3 {
                *e.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        for (&(x, y), &c) in &e {
            assert_eq!(c, 1);
            assert_eq!(e.get(&(y, x)), Some(&1), "an edge without its twin");
        }
        assert_eq!(
            verts.len() as i64 - e.len() as i64 / 2 + tris.len() as i64,
            2
        );
    }

    #[test]
    fn a_cube_with_points_inside_is_its_eight_corners() {
        let mut pts = Vec::new();
        let mut seed = 7;
        for _ in 0..500 {
            pts.push(DVec3::new(lcg(&mut seed), lcg(&mut seed), lcg(&mut seed)) * 2.0 - 1.0);
        }
        for i in 0..8 {
            let pick = |b: usize| if i & b != 0 { 1.0 } else { -1.0 };
            pts.push(DVec3::new(pick(1), pick(2), pick(4)));
        }
        let (v, t) = hull(&pts, 1e-12).unwrap();
        check(&pts, &v, &t, 1e-12);
        assert_eq!(v.len(), 8);
        assert_eq!(t.len(), 12);
        for p in &v {
            assert_eq!(p.abs(), DVec3::ONE);
        }
        // Points on the faces and edges may stay as corners of coplanar
        // triangles (found before the cube's corners), but the solid is the
        // cube: volume 8, every corner on its surface.
        pts.insert(0, DVec3::new(1.0, 0.3, -0.2));
        pts.insert(0, DVec3::new(1.0, 1.0, 0.5));
        let (v, t) = hull(&pts, 1e-12).unwrap();
        check(&pts, &v, &t, 1e-12);
        let volume: f64 = t
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| v[i as usize]);
                a.dot(b.cross(c))
            })
            .sum::<f64>()
            / 6.0;
        assert!((volume - 8.0).abs() < 1e-12, "{volume}");
        assert!(v.iter().all(|p| p.abs().max_element() == 1.0));
    }

    #[test]
    fn points_on_a_sphere_are_all_vertices() {
        let mut pts = Vec::new();
        let mut seed = 3;
        for _ in 0..2000 {
            let z = lcg(&mut seed) * 2.0 - 1.0;
            let a = lcg(&mut seed) * std::f64::consts::TAU;
            let r = (1.0 - z * z).sqrt();
            pts.push(DVec3::new(r * a.cos(), r * a.sin(), z) * 10.0 + DVec3::splat(1e3));
        }
        let (v, t) = hull(&pts, 1e-9).unwrap();
        check(&pts, &v, &t, 1e-9);
        assert_eq!(v.len(), 2000);
        assert_eq!(t.len(), 2 * 2000 - 4);
    }

    #[test]
    fn flat_points_have_no_hull() {
        let pts: Vec<DVec3> = (0..20)
            .map(|i| DVec3::new(i as f64, (i * i % 7) as f64, 0.0))
            .collect();
        assert!(hull(&pts, 1e-12).is_none());
        assert!(hull(&pts[..3], 1e-12).is_none());
    }
}
