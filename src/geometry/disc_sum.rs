//! A polytope plus a flat disc, P ⊕ E, written out as exact primitives:
//! the hull of cylinders whose discs are one disc moved (a plate rounded at
//! its corners with a sloped or lofted side, a tapered rounded box, a
//! slot between two heights) and the sum of polytopes and such a hull
//! (OpenSCAD's rounded box, `minkowski() { cube(…); cylinder(…); }`). They
//! render at the speed of those primitives, not of support-function casts.
//!
//! Take the frame in which E is the unit disc of the plane z = 0 (an
//! affine map of the world; E an ellipse there). The section of P ⊕ E at
//! height z is the section of P at z offset by 1 in its plane, and a
//! convex polygon offset by 1 is the polygon, each edge's rectangle pushed
//! out along the edge's outward normal, and each corner's disc. An edge of
//! a section is where a face F of P crosses that height, and its outward
//! normal in the plane is u_F, the unit horizontal part of F's normal; a
//! corner is where an edge of P crosses it. So over all heights P ⊕ E is
//! P, each face swept along u_F (F ⊕ [0, u_F]; nothing for a horizontal
//! face), and each edge that is not horizontal swept by the disc along
//! it, an oblique cylinder with circular sections (a horizontal edge's
//! sweep is flat). P with its faces pushed out is one closed mesh — the
//! pushed faces, the horizontal faces where they are, and along each edge
//! the walls from it to its faces' pushed copies, across each section the
//! chords of a corner's disc — and the edges' sweeps are cylinders.

use glam::{DAffine3, DMat3, DVec3};

use crate::geometry::ball_sum::{hull_faces, plane_hull, span, Pieces, Span};
use crate::geometry::convex::ConvexPart;
use crate::geometry::polytope::points_tolerance;
use crate::geometry::{Cone, Shape};
use crate::plane::hull::MAX_HULL_POINTS;

/// A cylinder part (equal radii) placed in the world: its two axis ends
/// and the disc's half-axes.
struct Placed {
    ends: [DVec3; 2],
    axes: [DVec3; 2],
}

fn cylinder(p: &ConvexPart) -> Option<Placed> {
    let Shape::Cone(c) = &p.shape else {
        return None;
    };
    if c.r0 != c.r1 || c.r0 <= 0.0 {
        return None;
    }
    let m = &p.to_world;
    let z0 = super::cone::bottom(c.centered);
    Some(Placed {
        ends: [
            m.transform_point3(DVec3::Z * z0),
            m.transform_point3(DVec3::Z * (z0 + 1.0)),
        ],
        axes: [m.matrix3.x_axis * c.r0, m.matrix3.y_axis * c.r0],
    })
}

/// The disc's shape: Σ aᵢaᵢᵀ over its half-axes, the same for every
/// placement of one disc (an ellipse {A·u : |u| ≤ 1} is fixed by AAᵀ).
pub fn shape_of(axes: &[DVec3; 2]) -> DMat3 {
    let outer = |a: DVec3| DMat3::from_cols(a * a.x, a * a.y, a * a.z);
    outer(axes[0]) + outer(axes[1])
}

/// P ⊕ E as pieces (in the parts' frame) when `hulls` (a Minkowski sum of
/// hulls) is one: one hull holds cylinders whose discs are one disc E
/// (10⁻¹² of its size), and whatever else it holds is a polytope inside
/// the hull of those cylinders (each corner within 10⁻⁹ of the set's size
/// of one cylinder or of the hull of their axes); every other hull is of
/// polytopes. `None` otherwise, past [`MAX_HULL_POINTS`] corners of P, or
/// when the sum is flat.
pub fn as_disc_sum(hulls: &[Vec<ConvexPart>]) -> Option<Pieces> {
    let with = hulls
        .iter()
        .position(|h| h.iter().any(|p| cylinder(p).is_some()))?;
    let cyls: Vec<Placed> = hulls[with].iter().filter_map(cylinder).collect();
    let s0 = shape_of(&cyls[0].axes);
    let size = s0
        .to_cols_array()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for c in &cyls[1..] {
        let d = shape_of(&c.axes) - s0;
        if d.to_cols_array().iter().any(|v| v.abs() > 1e-12 * size) {
            return None;
        }
    }
    // The frame: E's half-axes and their normal, at the first end.
    let [a1, a2] = cyls[0].axes;
    let n = a1.cross(a2);
    let l = DMat3::from_cols(a1, a2, n / n.length().sqrt());
    let frame = DAffine3::from_mat3_translation(l, cyls[0].ends[0]);
    let local = frame.inverse();
    if !local.is_finite() {
        return None;
    }
    let ends: Vec<DVec3> = cyls
        .iter()
        .flat_map(|c| c.ends.map(|e| local.transform_point3(e)))
        .collect();
    let mut others: Vec<DVec3> = Vec::new();
    let mut sum: Vec<DVec3> = ends.clone();
    for (k, h) in hulls.iter().enumerate() {
        let mut corners = Vec::new();
        for p in h {
            if k == with && cylinder(p).is_some() {
                continue;
            }
            if cylinder(p).is_some() {
                return None;
            }
            corners.extend(p.corners()?.into_iter().map(|q| local.transform_point3(q)));
        }
        if k == with {
            others = corners;
        } else if !corners.is_empty() {
            sum = minkowski(&vertices(&sum)?, &vertices(&corners)?)?;
        }
    }
    let pts = vertices(&sum)?;
    let tol = points_tolerance(&pts);
    // The hull's own polytopes must lie inside the hull of its cylinders.
    if !others.is_empty() {
        let axes = vertices(&ends)?;
        let faces = if axes.len() >= 4 {
            hull_faces(&axes, points_tolerance(&axes))
        } else {
            Vec::new()
        };
        let near = 1e-9 * scale(&ends).max(1.0);
        let inside = |q: DVec3| {
            (faces.len() >= 4
                && faces
                    .iter()
                    .all(|(n, ring)| (q - axes[ring[0]]).dot(*n) <= near))
                || cyls.iter().any(|c| {
                    let [a, b] = c.ends.map(|e| local.transform_point3(e));
                    in_frustum(q, (a, 1.0), (b, 1.0), near)
                })
        };
        if !others.iter().all(|&q| inside(q)) {
            return None;
        }
    }
    let mut out = Pieces { parts: Vec::new() };
    let world = |p: DVec3| frame.transform_point3(p);
    let sweep = |out: &mut Pieces, a: DVec3, b: DVec3| {
        if (b.z - a.z).abs() > tol {
            let m =
                DAffine3::from_mat3_translation(DMat3::from_cols(a1, a2, l * (b - a)), world(a));
            let cone = Cone {
                r0: 1.0,
                r1: 1.0,
                centered: false,
            };
            out.parts.push((Shape::Cone(cone), m));
        }
    };
    match span(&pts, tol) {
        Span::Point => None,
        Span::Segment(a, b) => {
            sweep(&mut out, a, b);
            (!out.parts.is_empty()).then_some(out)
        }
        Span::Plane(n) => {
            let poly = plane_hull(&pts, pts[0], n, tol);
            let (lo, hi) = poly
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    (l.min(p.z), h.max(p.z))
                });
            if hi - lo <= tol {
                return None;
            }
            let u = horizontal(n);
            out.prism(
                poly.iter().map(|&p| world(p + u)).collect(),
                poly.iter().map(|&p| world(p - u)).collect(),
            );
            for i in 0..poly.len() {
                sweep(&mut out, poly[i], poly[(i + 1) % poly.len()]);
            }
            Some(out)
        }
        Span::Solid => {
            let faces = hull_faces(&pts, tol);
            solid(&mut out, &pts, &faces, tol, &world);
            for (a, b) in edges(&faces) {
                sweep(&mut out, pts[a], pts[b]);
            }
            Some(out)
        }
    }
}

/// P with each face pushed out along its unit horizontal direction (a
/// horizontal face left where it is), as one closed mesh in the world.
fn solid(
    out: &mut Pieces,
    pts: &[DVec3],
    faces: &[(DVec3, Vec<usize>)],
    tol: f64,
    world: &dyn Fn(DVec3) -> DVec3,
) {
    let mut push: Vec<Option<DVec3>> = faces
        .iter()
        .map(|(n, ids)| {
            let (lo, hi) = ids
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &q| {
                    (l.min(pts[q].z), h.max(pts[q].z))
                });
            (hi - lo > tol).then(|| horizontal(*n))
        })
        .collect();
    // Faces meeting at an edge with one horizontal direction (a crease
    // across it, the edge horizontal) move as one: the same vector, so
    // that their pushed edges coincide and the walls between them, which
    // would be one quad twice, are left out.
    let shared = edge_faces(faces);
    for &(_, f, g) in &shared {
        if let (Some(a), Some(b)) = (push[f], push[g]) {
            if a != b && (a - b).length() <= 1e-9 {
                let keep = a;
                for p in push.iter_mut() {
                    if *p == Some(b) {
                        *p = Some(keep);
                    }
                }
            }
        }
    }
    let mut verts: Vec<DVec3> = pts.iter().map(|&p| world(p)).collect();
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for (f, (_, ids)) in faces.iter().enumerate() {
        let k = ids.len() as u32;
        let Some(u) = push[f] else {
            for i in 1..k as usize - 1 {
                tris.push([ids[0], ids[i], ids[i + 1]].map(|q| q as u32));
            }
            continue;
        };
        // The fault: faces pushed 1 % short of the disc's rim.
        let reach = if crate::mutant::active("disc_push_short") {
            u * 0.99
        } else {
            u
        };
        let base = verts.len() as u32;
        verts.extend(ids.iter().map(|&q| world(pts[q] + reach)));
        for i in 1..k - 1 {
            tris.push([base, base + i, base + i + 1]);
        }
        for i in 0..k {
            let j = (i + 1) % k;
            let (a, b) = (ids[i as usize], ids[j as usize]);
            let other = shared
                .iter()
                .find(|e| e.0 == (a.min(b), a.max(b)))
                .map(|e| if e.1 == f { e.2 } else { e.1 });
            if other.is_some_and(|g| push[g] == Some(u)) {
                continue;
            }
            let (a, b) = (a as u32, b as u32);
            tris.push([a, b, base + j]);
            tris.push([a, base + j, base + i]);
        }
    }
    out.mesh(verts, tris);
}

/// The unit horizontal part of the normal of a face that is not
/// horizontal.
fn horizontal(n: DVec3) -> DVec3 {
    DVec3::new(n.x, n.y, 0.0).normalize()
}

/// Each edge of the faces (its two points, the lower first) with the two
/// faces that meet there.
fn edge_faces(faces: &[(DVec3, Vec<usize>)]) -> Vec<((usize, usize), usize, usize)> {
    let mut seen: Vec<((usize, usize), usize)> = Vec::new();
    let mut out = Vec::new();
    for (f, (_, ids)) in faces.iter().enumerate() {
        for i in 0..ids.len() {
            let (a, b) = (ids[i], ids[(i + 1) % ids.len()]);
            let e = (a.min(b), a.max(b));
            match seen.iter().find(|s| s.0 == e) {
                Some(&(_, g)) => out.push((e, g, f)),
                None => seen.push((e, f)),
            }
        }
    }
    out
}

/// The edges of the faces, each once.
fn edges(faces: &[(DVec3, Vec<usize>)]) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = Vec::new();
    for (_, ids) in faces {
        for i in 0..ids.len() {
            let (a, b) = (ids[i], ids[(i + 1) % ids.len()]);
            let e = (a.min(b), a.max(b));
            if !out.contains(&e) {
                out.push(e);
            }
        }
    }
    out
}

/// Whether q is within `near` of the frustum of circular sections between
/// discs a and b.
pub fn in_frustum(q: DVec3, a: (DVec3, f64), b: (DVec3, f64), near: f64) -> bool {
    let dz = b.0.z - a.0.z;
    if dz.abs() <= near {
        return false;
    }
    let s = (q.z - a.0.z) / dz;
    let ds = near / dz.abs();
    let t = s.clamp(0.0, 1.0);
    let c = a.0 + (b.0 - a.0) * t;
    let r = a.1 + (b.1 - a.1) * t;
    (-ds..=1.0 + ds).contains(&s) && (q.truncate() - c.truncate()).length() <= r + near
}

/// The corners of the hull of `pts` (all of them, deduplicated, when they
/// span no volume); `None` past [`MAX_HULL_POINTS`].
pub fn vertices(pts: &[DVec3]) -> Option<Vec<DVec3>> {
    let mut v = match super::quickhull::hull(pts, points_tolerance(pts)) {
        Some((v, _)) => v,
        None => pts.to_vec(),
    };
    v.sort_by(|a, b| {
        a.to_array()
            .partial_cmp(&b.to_array())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    v.dedup();
    (v.len() <= MAX_HULL_POINTS).then_some(v)
}

/// Every sum of a point of `a` and one of `b`.
pub fn minkowski(a: &[DVec3], b: &[DVec3]) -> Option<Vec<DVec3>> {
    (a.len() * b.len() <= 8 * MAX_HULL_POINTS * MAX_HULL_POINTS).then(|| {
        a.iter()
            .flat_map(|&p| b.iter().map(move |&q| p + q))
            .collect()
    })
}

/// The points' extent and distance from the origin, the larger.
pub fn scale(pts: &[DVec3]) -> f64 {
    let p0 = pts[0];
    pts.iter().fold(0.0f64, |s, p| {
        s.max((*p - p0).abs().max_element())
            .max(p.abs().max_element())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cyl(at: DVec3, r: f64, h: f64) -> ConvexPart {
        ConvexPart {
            shape: Shape::Cone(Cone {
                r0: 1.0,
                r1: 1.0,
                centered: false,
            }),
            to_world: DAffine3::from_scale_rotation_translation(
                DVec3::new(r, r, h),
                glam::DQuat::IDENTITY,
                at,
            ),
        }
    }

    fn count(p: &Pieces, name: &str) -> usize {
        p.parts.iter().filter(|(s, _)| s.name() == name).count()
    }

    #[test]
    fn cylinders_at_two_heights_are_a_mesh_and_their_slanted_edges() {
        // Four cylinders at the corners of a rectangle, two raised: P is a
        // box sheared along y; its four upright edges and the four slanted
        // ones across the raised side are cylinders, its four edges along
        // x are horizontal.
        let parts = vec![
            cyl(DVec3::ZERO, 2.0, 1.0),
            cyl(DVec3::new(10.0, 0.0, 0.0), 2.0, 1.0),
            cyl(DVec3::new(0.0, 8.0, 3.0), 2.0, 1.0),
            cyl(DVec3::new(10.0, 8.0, 3.0), 2.0, 1.0),
        ];
        let p = as_disc_sum(&[parts]).unwrap();
        assert_eq!((count(&p, "polyhedron"), count(&p, "cylinder")), (1, 8));
    }

    #[test]
    fn discs_of_different_radii_are_not_one_disc() {
        let parts = vec![cyl(DVec3::ZERO, 2.0, 1.0), cyl(DVec3::X * 9.0, 2.5, 1.0)];
        assert!(as_disc_sum(&[parts]).is_none());
    }

    #[test]
    fn a_box_sticking_out_of_the_cylinders_hull_is_refused() {
        let cube = |at: DVec3, s: f64| ConvexPart {
            shape: Shape::Cuboid(crate::geometry::Cuboid { centered: false }),
            to_world: DAffine3::from_scale_rotation_translation(
                DVec3::splat(s),
                glam::DQuat::IDENTITY,
                at,
            ),
        };
        let c = vec![cyl(DVec3::ZERO, 2.0, 1.0), cyl(DVec3::X * 9.0, 2.0, 1.0)];
        let mut inside = c.clone();
        inside.push(cube(DVec3::new(0.0, -1.0, 0.0), 1.0));
        assert!(as_disc_sum(&[inside]).is_some());
        let mut out = c;
        out.push(cube(DVec3::new(0.0, -1.0, 0.0), 3.0));
        assert!(as_disc_sum(&[out]).is_none());
    }
}
