//! Each primitive on its own, in the manner of pbrt-v4's `shapes_test.cpp`:
//! re-intersection from a surface point finds nothing closer, the cube's
//! edges and corners and the cone's and cylinder's cap rims have no cracks,
//! and every normal agrees with the primitive's own inside test (finite
//! differences: just off the surface along directions 1° above the tangent
//! plane is outside, 1° below is inside).

use csgrt::csg::{Csg, Primitive, SurfaceHit};
use csgrt::geometry::{Cone, Cuboid, Ray, Shape, Sphere, Torus, Transform};
use csgrt::math::robust::{offset_origin, point_error};
use csgrt::stats::Stats;
use glam::{DAffine3, DQuat, DVec3};

use crate::common::{
    curved_lathe, curved_prism, hull_and_sum, l_lathe, l_offset, l_prism, l_shadow, l_twisted,
    octahedron, rounded_box, Rng,
};

fn shapes() -> Vec<(&'static str, Shape)> {
    vec![
        ("prism", l_prism(1.0)),
        ("tapered prism", l_prism(0.4)),
        ("widening prism", l_prism(1.7)),
        ("pyramid", l_prism(0.0)),
        ("curved prism", curved_prism(1.0)),
        ("curved tapered prism", curved_prism(0.3)),
        ("curved widening prism", curved_prism(2.5)),
        ("twisted prism", l_twisted(2.5, glam::DVec2::ONE)),
        (
            "twisted tapered prism",
            l_twisted(-7.0, glam::DVec2::new(0.6, 1.4)),
        ),
        (
            "unevenly scaled prism",
            l_twisted(0.0, glam::DVec2::new(0.2, 1.8)),
        ),
        ("twisted pyramid", l_twisted(3.0, glam::DVec2::ZERO)),
        ("lathe", l_lathe()),
        ("curved lathe", curved_lathe()),
        ("sphere", Shape::Sphere(Sphere)),
        ("cube", Shape::Cuboid(Cuboid { centered: false })),
        ("centred cube", Shape::Cuboid(Cuboid { centered: true })),
        (
            "cylinder",
            Shape::Cone(Cone {
                r0: 1.0,
                r1: 1.0,
                centered: false,
            }),
        ),
        (
            "cone",
            Shape::Cone(Cone {
                r0: 1.0,
                r1: 0.0,
                centered: true,
            }),
        ),
        (
            "frustum",
            Shape::Cone(Cone {
                r0: 0.4,
                r1: 1.0,
                centered: false,
            }),
        ),
        ("torus", Shape::Torus(Torus { minor: 0.35 })),
        ("spindle torus's apple", Shape::Torus(Torus { minor: 1.4 })),
        (
            "turned slanted ellipse",
            Shape::Ring(
                csgrt::geometry::Ring::new(glam::DMat2::from_cols_array(&[0.5, 0.3, -0.15, 0.25]))
                    .unwrap(),
            ),
        ),
        ("mesh", octahedron()),
        ("hull of two balls", hull_and_sum()[0].clone()),
        ("box plus ball", hull_and_sum()[1].clone()),
        ("rounded box", rounded_box()),
        ("shadow", l_shadow()),
        ("grown offset prism", l_offset(0.3)),
        ("shrunk offset prism", l_offset(-0.2)),
    ]
}

/// Which solid a shape is: a match with no wildcard, so that a new solid
/// does not compile here until it is given a place in [`shapes`].
fn solid_index(s: &Shape) -> usize {
    match s {
        Shape::Sphere(_) => 0,
        Shape::Cuboid(_) => 1,
        Shape::Cone(_) => 2,
        Shape::Torus(_) => 3,
        Shape::Halfspace(_) => 4,
        Shape::Prism(_) => 5,
        Shape::Lathe(_) => 6,
        Shape::Twisted(_) => 7,
        Shape::Mesh(_) => 8,
        Shape::Shadow(_) => 9,
        Shape::Convex(_) => 10,
        Shape::Rounded(_) => 11,
        Shape::OffsetPrism(_) => 12,
        Shape::Ring(_) => 13,
    }
}

#[test]
fn every_solid_has_the_properties_checked() {
    let mut seen = [false; 14];
    for (_, s) in shapes() {
        seen[solid_index(&s)] = true;
    }
    // The half-space is unbounded: no inner point to aim at, no far side;
    // `support_points_…` checks that it has no support point.
    seen[solid_index(&Shape::Halfspace(csgrt::geometry::Halfspace))] = true;
    let missing: Vec<usize> = (0..14).filter(|&i| !seen[i]).collect();
    assert!(
        missing.is_empty(),
        "solids missing from shapes(): {missing:?}"
    );
}

/// Placements: plain, turned and stretched, and small and far away.
fn placements() -> Vec<DAffine3> {
    vec![
        DAffine3::IDENTITY,
        DAffine3::from_scale_rotation_translation(
            DVec3::new(1.5, 0.6, 2.2),
            DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.9),
            DVec3::new(3.0, -1.0, 0.5),
        ),
        DAffine3::from_scale_rotation_translation(
            DVec3::splat(1e-3),
            DQuat::from_axis_angle(DVec3::new(-0.3, 0.2, 1.0).normalize(), 2.1),
            DVec3::new(1e5, 2e5, -7e4),
        ),
    ]
}

fn single(shape: &Shape, m: DAffine3) -> Csg {
    let mut csg = Csg::default();
    let root = csg.add_prim(Primitive::new(shape.clone(), Transform::new(m).unwrap(), 0));
    csg.root = Some(root);
    csg
}

fn first(csg: &Csg, ray: &Ray) -> Option<SurfaceHit> {
    csg.first_hit(ray, 0.0, f64::INFINITY, &mut Stats::default())
}

fn size_of(m: &DAffine3) -> f64 {
    m.matrix3.x_axis.length()
}

/// A point inside the primitive, in object space.
fn inner_point(shape: &Shape) -> DVec3 {
    match shape {
        Shape::Torus(_) | Shape::Ring(_) => DVec3::new(1.0, 0.0, 0.0),
        // In the L's lower-left square, at a quarter of the height (its
        // section scaled by the taper there).
        Shape::Prism(p) => {
            let w = 1.0 + (p.top - 1.0) * 0.25;
            let z = if p.centered { -0.25 } else { 0.25 };
            DVec3::new(0.5 * w, 0.5 * w, z)
        }
        Shape::Lathe(_) => DVec3::new(1.0, 0.0, -0.5),
        // In the L's lower-left square, half way up.
        Shape::OffsetPrism(_) | Shape::Shadow(_) => DVec3::new(0.5, 0.5, 0.5),
        // The same point of the section, where the twist and scale put it.
        Shape::Twisted(t) => {
            let z = 0.25;
            let s = glam::DVec2::ONE + (t.scale - glam::DVec2::ONE) * z;
            let p = glam::DMat2::from_angle(-t.twist * z) * glam::DVec2::splat(0.5);
            (p * s).extend(if t.centered { z - 0.5 } else { z })
        }
        s => s.object_bounds().center(),
    }
}

/// Hits on the primitive from rays aimed at inner points from all around.
fn surface_hits(
    csg: &Csg,
    shape: &Shape,
    m: &DAffine3,
    rng: &mut Rng,
    n: usize,
) -> Vec<(Ray, SurfaceHit)> {
    let size = size_of(m);
    let mut out = Vec::new();
    while out.len() < n {
        let inner = inner_point(shape) + (rng.unit() * 0.2);
        if !shape.contains(inner) {
            // Beyond a twisted section's turn: aim elsewhere.
            continue;
        }
        let target = m.transform_point3(inner);
        let eye = target + rng.unit() * 6.0 * size * 2.0;
        let ray = Ray::new(eye, (target - eye).normalize());
        let hit = first(csg, &ray).expect("a ray aimed inside the solid hits it");
        out.push((ray, hit));
    }
    out
}

#[test]
fn reintersection_from_a_surface_point_finds_nothing_closer() {
    let mut rng = Rng(1);
    for (name, shape) in shapes() {
        for m in placements() {
            let csg = single(&shape, m);
            let size = size_of(&m);
            for (ray, hit) in surface_hits(&csg, &shape, &m, &mut rng, 200) {
                let n = hit.normal;
                let err = point_error(hit.point, ray.origin, hit.t * ray.dir);
                // Going on along the ray: the next crossing is the far side,
                // never the point just left.
                let on = Ray::new(offset_origin(hit.point, n, err, ray.dir), ray.dir);
                let next = first(&csg, &on).expect("a ray that entered leaves");
                assert!(
                    next.t > 1e-6 * size,
                    "{name}: re-hit at t = {} after entering at {:?}",
                    next.t,
                    hit.point
                );
                assert!(
                    next.normal.dot(ray.dir) > 0.0,
                    "{name}: the next crossing must leave"
                );
                // Leaving in any outward direction: a convex solid is never
                // met again; the torus and the ring only far from the point.
                let mut out = rng.unit();
                if out.dot(n) < 0.0 {
                    out = -out;
                }
                if out.dot(n) < 1e-3 {
                    continue;
                }
                let away = Ray::new(offset_origin(hit.point, n, err, out), out);
                match first(&csg, &away) {
                    None => {}
                    Some(h)
                        if matches!(
                            shape,
                            Shape::Torus(_)
                                | Shape::Ring(_)
                                | Shape::Prism(_)
                                | Shape::Lathe(_)
                                | Shape::Twisted(_)
                                | Shape::OffsetPrism(_)
                                | Shape::Shadow(_)
                        ) =>
                    {
                        assert!(h.t > 1e-6 * size, "{name}: re-hit at t = {}", h.t)
                    }
                    Some(h) => panic!("{name}: a ray leaving a convex solid hit it at t = {}", h.t),
                }
            }
        }
    }
}

/// Points exactly on the cube's 12 edges and 8 corners, and on the
/// cylinder's, frustum's and cone's cap rims, in object space, with a
/// point well inside.
fn seams(shape: &Shape) -> Option<(Vec<DVec3>, DVec3)> {
    let steps = 16;
    match shape.clone() {
        Shape::Cuboid(Cuboid { centered }) => {
            let lo = if centered { -1.0 } else { 0.0 };
            let mut pts = Vec::new();
            for axis in 0..3 {
                for corner in 0..4 {
                    for k in 0..=steps {
                        let mut p = DVec3::splat(lo);
                        p[axis] = lo + (1.0 - lo) * k as f64 / steps as f64;
                        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                        p[a] = if corner & 1 == 0 { lo } else { 1.0 };
                        p[b] = if corner & 2 == 0 { lo } else { 1.0 };
                        pts.push(p);
                    }
                }
            }
            Some((pts, DVec3::splat((lo + 1.0) / 2.0)))
        }
        Shape::Cone(Cone { r0, r1, centered }) => {
            let z0 = if centered { -0.5 } else { 0.0 };
            let mut pts = Vec::new();
            for (z, r) in [(z0, r0), (z0 + 1.0, r1)] {
                for k in 0..64 {
                    let a = std::f64::consts::TAU * k as f64 / 64.0;
                    pts.push(DVec3::new(r * a.cos(), r * a.sin(), z));
                }
            }
            Some((pts, DVec3::new(0.0, 0.0, z0 + 0.5)))
        }
        _ => None,
    }
}

#[test]
fn no_cracks_at_cube_edges_and_cap_rims() {
    for (name, shape) in shapes() {
        let Some((points, middle)) = seams(&shape) else {
            continue;
        };
        for m in placements() {
            let csg = single(&shape, m);
            let size = size_of(&m);
            let mid = m.transform_point3(middle);
            for p in points.iter().map(|p| m.transform_point3(*p)) {
                let dist = (p - mid).length();
                if dist < 1e-9 * size {
                    continue; // the cone's apex seen from its own axis
                }
                // From inside out through the seam: leaves exactly there.
                let dir = (p - mid) / dist;
                let hit = first(&csg, &Ray::new(mid, dir))
                    .unwrap_or_else(|| panic!("{name}: a crack at {p:?} (from inside)"));
                let scale = mid.abs().max_element() + dist;
                assert!(
                    (hit.t - dist).abs() <= 1e-12 * scale,
                    "{name}: left at t = {}, the seam is at {dist}",
                    hit.t
                );
                // From outside in through the seam towards the middle.
                let eye = p + dir * 5.0 * size;
                let hit = first(&csg, &Ray::new(eye, -dir))
                    .unwrap_or_else(|| panic!("{name}: a crack at {p:?} (from outside)"));
                let scale = eye.abs().max_element() + 5.0 * size;
                assert!(
                    (hit.t - 5.0 * size).abs() <= 1e-12 * scale,
                    "{name}: entered at t = {}, the seam is at {}",
                    hit.t,
                    5.0 * size
                );
            }
        }
    }
}

#[test]
fn normals_agree_with_the_inside_test() {
    let mut rng = Rng(7);
    // A direction 1° above the tangent plane leaves the solid, 1° below
    // enters it. The step is 1e-6 of the size, or 2048 ulps of the
    // coordinates where that is larger (a part of 1e-3 at 1e5: its normal
    // part is then 36 ulps, well clear of the rounding of the point and of
    // its mapping into object space); either way the surface's curvature
    // bends it by far less than 1° over the step, so a normal off by more
    // fails.
    let tilt = 1f64.to_radians();
    for (name, shape) in shapes() {
        for m in placements() {
            let csg = single(&shape, m);
            let root = csg.root.unwrap();
            let size = size_of(&m);
            for (_, hit) in surface_hits(&csg, &shape, &m, &mut rng, 100) {
                let n = hit.normal;
                assert!(
                    (n.length() - 1.0).abs() < 1e-12,
                    "{name}: |n| = {}",
                    n.length()
                );
                let step = (1e-6 * size).max(2048.0 * f64::EPSILON * hit.point.abs().max_element());
                // Points near edges see two faces: only judge the smooth part.
                let near_edge = |q: DVec3| {
                    let o = csg.prims[0].xf.point_to_object(q);
                    seam_distance(&shape, o) < 4.0 * step / size
                };
                if near_edge(hit.point) {
                    continue;
                }
                let t1 = n.any_orthonormal_vector();
                let t2 = n.cross(t1);
                for k in 0..8 {
                    let a = std::f64::consts::TAU * k as f64 / 8.0;
                    let tangent = t1 * a.cos() + t2 * a.sin();
                    let up = tangent * tilt.cos() + n * tilt.sin();
                    let down = tangent * tilt.cos() - n * tilt.sin();
                    assert!(
                        !csg.contains(root, hit.point + up * step),
                        "{name}: 1° above the tangent plane is inside at {:?} (n = {n:?})",
                        hit.point
                    );
                    assert!(
                        csg.contains(root, hit.point + down * step),
                        "{name}: 1° below the tangent plane is outside at {:?} (n = {n:?})",
                        hit.point
                    );
                }
            }
        }
    }
}

/// How far an object-space surface point is from an edge of its solid.
fn seam_distance(shape: &Shape, p: DVec3) -> f64 {
    match shape.clone() {
        // A spindle torus's apple meets itself in two cusps on the axis.
        Shape::Torus(Torus { minor }) if minor >= 1.0 => {
            let h = (minor * minor - 1.0).sqrt();
            (p - DVec3::new(0.0, 0.0, h))
                .length()
                .min((p - DVec3::new(0.0, 0.0, -h)).length())
        }
        Shape::Cuboid(Cuboid { centered }) => {
            let lo = if centered { -1.0 } else { 0.0 };
            // Distances to the two nearest faces other than the one hit.
            let mut d: Vec<f64> = (0..3)
                .map(|i| (p[i] - lo).abs().min((p[i] - 1.0).abs()))
                .collect();
            d.sort_by(f64::total_cmp);
            d[1]
        }
        Shape::Cone(Cone { r0, r1, centered }) => {
            // The two rims are circles (the apex one of radius 0).
            let z = p.z - if centered { -0.5 } else { 0.0 };
            let rho = p.truncate().length();
            let rim = |zk: f64, rk: f64| (rho - rk).hypot(z - zk);
            rim(0.0, r0).min(rim(1.0, r1))
        }
        Shape::Prism(prism) => {
            // The cap rims and the vertical edges over the vertices.
            let q = p.truncate();
            let to_outline = prism
                .region
                .edges
                .iter()
                .map(|&(a, b)| {
                    let t = ((q - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    (a + (b - a) * t - q).length()
                })
                .fold(f64::INFINITY, f64::min);
            let to_vertex = prism
                .region
                .edges
                .iter()
                .map(|(a, _)| (*a - q).length())
                .fold(f64::INFINITY, f64::min);
            let to_cap = p.z.abs().min((p.z - 1.0).abs());
            if to_cap < to_outline {
                to_outline.max(to_cap)
            } else {
                to_cap.min(to_vertex)
            }
        }
        _ => f64::INFINITY,
    }
}

#[test]
fn support_points_are_the_farthest_points_of_the_solid() {
    // The support point lies on the solid (a step inwards is inside), and no
    // point of the solid lies farther along d: sampled from the object box
    // by the primitive's own inside test.
    let mut rng = Rng(11);
    for (name, shape) in shapes() {
        if matches!(&shape, Shape::Twisted(_))
            || matches!(&shape, Shape::OffsetPrism(o) if o.region.r < 0.0)
        {
            // No support function: a twisted side's farthest point is not a
            // vertex, and a shrunk outline's is not known exactly.
            assert!(shape.support(DVec3::X).is_none());
            continue;
        }
        let b = shape.object_bounds();
        let inside: Vec<DVec3> = (0..20000)
            .map(|_| b.min + (b.max - b.min) * DVec3::new(rng.next(), rng.next(), rng.next()))
            .filter(|p| shape.contains(*p))
            .collect();
        assert!(inside.len() > 1000, "{name}");
        for _ in 0..200 {
            let d = rng.unit() * rng.range(0.1, 10.0);
            let s = shape
                .support(d)
                .expect("a bounded solid has a support point");
            let u = d.normalize();
            // A step from s towards the inside: the middle of a convex
            // solid, or the tube's core for the torus; for a prism, whose
            // section need not be convex at its support, some step in the
            // section's plane (and towards the slab's middle).
            let on_solid = |core: DVec3| shape.contains(s + 1e-9 * (core - s));
            let found = match &shape {
                Shape::Torus(t) => on_solid(s - t.minor * u),
                Shape::Prism(p) => (0..64).any(|k| {
                    let (z_lo, z_mid) = if p.centered { (-0.5, 0.0) } else { (0.0, 0.5) };
                    let w = 1.0 + (p.top - 1.0) * (s.z - z_lo);
                    if k == 0 {
                        return on_solid(DVec3::new(0.5 * w, 0.5 * w, s.z));
                    }
                    let a = k as f64 * std::f64::consts::TAU / 64.0;
                    on_solid(s + DVec3::new(a.cos(), a.sin(), 0.01 * (z_mid - s.z)))
                }),
                Shape::Lathe(_) => on_solid((s.truncate().normalize_or_zero()).extend(-0.5)),
                // The L swept from 0 to 1: some step in its plane, towards
                // the slab's middle.
                Shape::OffsetPrism(_) | Shape::Shadow(_) => (0..64).any(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 64.0;
                    on_solid(s + DVec3::new(a.cos(), a.sin(), 0.01 * (0.5 - s.z)))
                }),
                _ => on_solid(shape.object_bounds().center()),
            };
            assert!(
                found,
                "{name}: support {s:?} along {d:?} is not on the solid"
            );
            let far = inside
                .iter()
                .map(|p| p.dot(u))
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(
                far <= s.dot(u) + 1e-12,
                "{name}: a point {far} beyond the support {}",
                s.dot(u)
            );
            // And it is tight: sampled points come close (a corner of the
            // centred cube is the worst sampled, about 0.1 short).
            assert!(
                far >= s.dot(u) - 0.3,
                "{name}: the support {} is far beyond every point ({far})",
                s.dot(u)
            );
        }
    }
    assert_eq!(
        Shape::Halfspace(csgrt::geometry::Halfspace).support(DVec3::Z),
        None
    );
}

/// Directions with zero, subnormal and negative-zero components (the
/// slab and quadratic divisions by them): every primitive, from every
/// placement, answers with a finite t and a unit normal; so do lines lying
/// in a side (where a side's function is zero all along: this hung).
#[test]
fn subnormal_and_zero_direction_components() {
    let tiny = [5e-324, 1e-310, 0.0, -1e-310, -0.0];
    let mut dirs = Vec::new();
    for e in tiny {
        dirs.push(DVec3::new(-1.0, 0.0, e));
        dirs.push(DVec3::new(-1.0, e, e));
        dirs.push(DVec3::new(e, e, -1.0));
        dirs.push(DVec3::new(e, -1.0, e));
    }
    for (name, shape) in shapes() {
        let csg = single(&shape, DAffine3::IDENTITY);
        for &d in &dirs {
            for x in [0.0, 0.5, 1.0, 5.0] {
                for z in [-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0] {
                    for target in [DVec3::new(x, 0.0, z), DVec3::new(5.0, x, z)] {
                        let ray = Ray::new(target - 10.0 * d, d);
                        if let Some(h) = first(&csg, &ray) {
                            assert!(h.t.is_finite(), "{name}: t = {} along {d:?}", h.t);
                            assert!(
                                (h.normal.length() - 1.0).abs() < 1e-9,
                                "{name}: normal {:?} along {d:?} to {target:?}",
                                h.normal
                            );
                        }
                    }
                }
            }
        }
        // A component below the smallest normal number changes nothing a
        // ray meets away from faces at its height: the same hits as with
        // that component zero.
        for e in tiny {
            let pairs = [
                (DVec3::new(-1.0, 0.0, e), DVec3::new(-1.0, 0.0, 0.0)),
                (DVec3::new(-1.0, e, e), DVec3::new(-1.0, 0.0, 0.0)),
                (DVec3::new(e, e, -1.0), DVec3::new(0.0, 0.0, -1.0)),
                (DVec3::new(e, -1.0, e), DVec3::new(0.0, -1.0, 0.0)),
            ];
            for (d, d0) in pairs {
                // Clear of the faces and edges of every shape, scaled or not.
                for x in [0.317, 0.736, 1.171] {
                    for z in [-0.713, -0.229, 0.268, 0.771] {
                        for target in [DVec3::new(x, 0.131, z), DVec3::new(0.934, x, z)] {
                            let hit = first(&csg, &Ray::new(target - 10.0 * d, d));
                            let hit0 = first(&csg, &Ray::new(target - 10.0 * d0, d0));
                            match (hit, hit0) {
                                (None, None) => {}
                                (Some(h), Some(h0)) => assert!(
                                    (h.t - h0.t).abs() < 1e-9,
                                    "{name}: t = {} along {d:?}, {} along {d0:?}, to {target:?}",
                                    h.t,
                                    h0.t
                                ),
                                (h, h0) => panic!(
                                    "{name}: {:?} along {d:?}, {:?} along {d0:?}, to {target:?}",
                                    h.map(|h| h.t),
                                    h0.map(|h| h.t)
                                ),
                            }
                        }
                    }
                }
            }
        }
        // Lines in the planes y = 0 and x = 0 (the L's sides lie in them,
        // and an untwisted extrusion's sides stay there at every height).
        for d in [DVec3::new(0.3, 0.0, 1.0), DVec3::new(0.0, -0.2, 1.0)] {
            let d = d.normalize();
            for x in [0.25, 0.5, 1.5] {
                let o = if d.y == 0.0 {
                    DVec3::new(x, 0.0, -5.0)
                } else {
                    DVec3::new(0.0, x, -5.0)
                };
                if let Some(h) = first(&csg, &Ray::new(o, d)) {
                    assert!(h.t.is_finite(), "{name}: t = {} along {d:?}", h.t);
                }
            }
        }
    }
}
