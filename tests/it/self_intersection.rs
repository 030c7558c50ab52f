//! A ray that leaves a surface does not hit that surface again: secondary
//! rays start from the hit point offset by its error bound
//! (`math::robust`), at every scale and distance from the origin.

use csgrt::csg::{Csg, Primitive};
use csgrt::geometry::{Cone, Cuboid, Ray, Shape, Sphere, Transform};
use csgrt::math::robust::{offset_origin, point_error};
use csgrt::stats::Stats;
use glam::{DAffine3, DQuat, DVec3};
use proptest::prelude::*;

use crate::common::{self, hull_and_sum, octahedron};

fn convex_shape() -> impl Strategy<Value = Shape> {
    let [hull, sum] = hull_and_sum();
    prop_oneof![
        Just(hull),
        Just(sum),
        Just(Shape::Sphere(Sphere)),
        Just(octahedron()),
        any::<bool>().prop_map(|centered| Shape::Cuboid(Cuboid { centered })),
        any::<bool>().prop_map(|centered| Shape::Cone(Cone {
            r0: 1.0,
            r1: 1.0,
            centered
        })),
        (0.0..=1.0f64, any::<bool>()).prop_map(|(r, centered)| Shape::Cone(Cone {
            r0: 1.0,
            r1: r,
            centered
        })),
    ]
}

fn unit(v: [f64; 3]) -> Option<DVec3> {
    let v = DVec3::from(v);
    (v.length() > 1e-3).then(|| v.normalize())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn leaving_a_convex_surface_never_hits_it_again(
        shape in convex_shape(),
        scale_exp in -3i32..=3,
        offset_exp in 0i32..=6,
        stretch in prop::array::uniform3(0.5..2.0f64),
        axis in prop::array::uniform3(-1.0..1.0f64),
        angle in 0.0..6.3f64,
        from in prop::array::uniform3(-1.0..1.0f64),
        bounce in prop::array::uniform3(-1.0..1.0f64),
    ) {
        let (Some(axis), Some(from), Some(bounce)) = (unit(axis), unit(from), unit(bounce)) else {
            return Ok(());
        };
        let size = 10f64.powi(scale_exp);
        let center = DVec3::new(1.0, -0.7, 0.4) * 10f64.powi(offset_exp);
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::from(stretch) * size, DQuat::from_axis_angle(axis, angle), center);
        let mut csg = Csg::default();
        let root = csg.add_prim(Primitive::new(shape.clone(), Transform::new(m).unwrap(), 0));
        csg.root = Some(root);
        let mut st = Stats::default();
        // A ray from outside towards the middle of the solid.
        let middle = m.transform_point3(shape.object_bounds().center());
        let eye = middle - from * 10.0 * size;
        let look = Ray::new(eye, from);
        // The middle of a convex solid's box is inside it, so the ray hits.
        let hit = csg.first_hit(&look, 0.0, f64::INFINITY, &mut st);
        prop_assert!(hit.is_some(), "a ray aimed at the middle missed (size {}, offset {})", size, center);
        let hit = hit.unwrap();
        let n = hit.normal;
        let err = point_error(hit.point, look.origin, hit.t * look.dir);
        // Leaving: any direction into the outer hemisphere.
        let out = if bounce.dot(n) > 0.0 { bounce } else { -bounce };
        if out.dot(n) > 1e-6 {
            let r = Ray::new(offset_origin(hit.point, n, err, out), out);
            let again = csg.first_hit(&r, 0.0, f64::INFINITY, &mut st);
            prop_assert!(again.is_none(), "hit again at {:?} (size {}, offset {})", again, size, center);
        }
        // Entering: the next hit is the far side, not the same point.
        let inward = -out;
        if inward.dot(n) < -1e-3 {
            let r = Ray::new(offset_origin(hit.point, n, err, inward), inward);
            let next = csg.first_hit(&r, 0.0, f64::INFINITY, &mut st);
            prop_assert!(next.is_some(), "an entering ray must leave the solid");
            let next = next.unwrap();
            prop_assert!(next.normal.dot(inward) > 0.0, "it must leave, not enter");
            prop_assert!(next.t > 1e-9 * size, "re-hit at t = {} (size {})", next.t, size);
        }
    }
}

/// A twisted or unevenly scaled extrusion: an ellipse anywhere in the
/// plane, or the L region of `tests/it/common`.
fn twisted_shape() -> impl Strategy<Value = Shape> {
    use csgrt::geometry::{TwistSection, Twisted};
    let ellipse = (
        prop::array::uniform4(-1.0..1.0f64),
        prop::array::uniform2(-1.0..1.0f64),
        -4.0..4.0f64,
        prop::array::uniform2(0.2..2.0f64),
        any::<bool>(),
    )
        .prop_filter_map("a flattened ellipse", |(m, c, twist, scale, centered)| {
            let m = glam::DMat2::from_cols_array(&m);
            (m.determinant().abs() > 0.05).then(|| {
                Shape::Twisted(Twisted {
                    section: TwistSection::Ellipse(glam::DAffine2::from_mat2_translation(
                        m,
                        glam::DVec2::from(c),
                    )),
                    twist,
                    scale: glam::DVec2::from(scale),
                    centered,
                })
            })
        });
    let region = (-4.0..4.0f64, prop::array::uniform2(0.2..2.0f64))
        .prop_map(|(twist, scale)| common::l_twisted(twist, glam::DVec2::from(scale)));
    prop_oneof![ellipse, region]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// Not convex, so only along the normal: leaving, the line does not
    /// meet the same side again nearby; entering, it meets a side where it
    /// leaves.
    #[test]
    fn leaving_a_twisted_side_along_its_normal_does_not_hit_it_again(
        shape in twisted_shape(),
        scale_exp in -3i32..=3,
        offset_exp in 0i32..=6,
        from in prop::array::uniform3(-1.0..1.0f64),
        aim in prop::array::uniform3(-0.3..0.3f64),
    ) {
        let Some(from) = unit(from) else { return Ok(()) };
        let size = 10f64.powi(scale_exp);
        let center = DVec3::new(1.0, -0.7, 0.4) * 10f64.powi(offset_exp);
        let m = DAffine3::from_scale_rotation_translation(DVec3::splat(size), DQuat::IDENTITY, center);
        let mut csg = Csg::default();
        let root = csg.add_prim(Primitive::new(shape.clone(), Transform::new(m).unwrap(), 0));
        csg.root = Some(root);
        let mut st = Stats::default();
        let b = shape.object_bounds();
        let target = m.transform_point3(b.center() + (b.max - b.min) * DVec3::from(aim));
        let look = Ray::new(target - from * 10.0 * size, from);
        let Some(hit) = csg.first_hit(&look, 0.0, f64::INFINITY, &mut st) else { return Ok(()) };
        let n = hit.normal;
        let err = point_error(hit.point, look.origin, hit.t * look.dir);
        let r = Ray::new(offset_origin(hit.point, n, err, n), n);
        if let Some(again) = csg.first_hit(&r, 0.0, f64::INFINITY, &mut st) {
            prop_assert!(again.t > 1e-6 * size, "hit again at t = {} (size {}, offset {})", again.t, size, center);
        }
        let r = Ray::new(offset_origin(hit.point, n, err, -n), -n);
        let next = csg.first_hit(&r, 0.0, f64::INFINITY, &mut st);
        prop_assert!(next.is_some(), "an entering ray must leave the solid");
        let next = next.unwrap();
        prop_assert!(next.normal.dot(-n) > 0.0, "it must leave, not enter (t = {})", next.t);
        prop_assert!(next.t > 1e-6 * size, "re-hit at t = {} (size {})", next.t, size);
    }
}
