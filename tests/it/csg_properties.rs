//! For random CSG trees of random transformed primitives, the spans along
//! random rays agree with a point-in-solid classification (each
//! primitive's own inside test, combined by the operations) of points
//! sampled along the line independently of the spans — a dense grid over
//! the whole stretch where the solids lie — and of points between the
//! reported boundaries.

use csgrt::csg::spans::{contains, Boundary, Span};
use csgrt::csg::{Csg, Primitive};
use csgrt::geometry::{Cone, Cuboid, Halfspace, Ray, Shape, Sphere, Torus, Transform};
use csgrt::math::boolean::Op;
use csgrt::stats::Stats;
use glam::{DAffine3, DQuat, DVec3};
use proptest::prelude::*;

use crate::common;
use crate::common::l_prism;

fn arb_shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        Just(Shape::Sphere(Sphere)),
        any::<bool>().prop_map(|centered| Shape::Cuboid(Cuboid { centered })),
        (0.0..=1.0f64, any::<bool>(), any::<bool>()).prop_map(|(r, top, centered)| if top {
            Shape::Cone(Cone {
                r0: 1.0,
                r1: r,
                centered,
            })
        } else {
            Shape::Cone(Cone {
                r0: r,
                r1: 1.0,
                centered,
            })
        }),
        any::<bool>().prop_map(|centered| Shape::Cone(Cone {
            r0: 1.0,
            r1: 1.0,
            centered
        })),
        (0.1..0.7f64).prop_map(|minor| Shape::Torus(Torus { minor })),
        Just(Shape::Halfspace(Halfspace)),
        Just(l_prism(1.0)),
        Just(l_prism(0.5)),
        Just(common::curved_prism(1.0)),
        Just(common::l_twisted(2.0, glam::DVec2::new(0.5, 1.2))),
        Just(common::curved_prism(0.6)),
        Just(common::l_lathe()),
        Just(common::curved_lathe()),
    ]
}

/// Rotation, non-uniform scale (sometimes mirrored) and translation.
fn arb_transform() -> impl Strategy<Value = DAffine3> {
    (
        prop::array::uniform3(-1.0..1.0f64),
        0.0..std::f64::consts::TAU,
        prop::array::uniform3(0.3..2.0f64),
        prop::array::uniform3(any::<bool>()),
        prop::array::uniform3(-1.5..1.5f64),
    )
        .prop_map(|(axis, angle, scale, mirror, t)| {
            let axis = DVec3::from(axis);
            let axis = if axis.length() < 1e-3 {
                DVec3::Z
            } else {
                axis.normalize()
            };
            let s = DVec3::new(
                if mirror[0] { -scale[0] } else { scale[0] },
                if mirror[1] { -scale[1] } else { scale[1] },
                scale[2],
            );
            DAffine3::from_scale_rotation_translation(
                s,
                DQuat::from_axis_angle(axis, angle),
                t.into(),
            )
        })
}

#[derive(Clone, Debug)]
enum Tree {
    Leaf(Shape, DAffine3),
    Node(Op, Vec<Tree>),
}

fn arb_tree() -> impl Strategy<Value = Tree> {
    let leaf = (arb_shape(), arb_transform()).prop_map(|(s, m)| Tree::Leaf(s, m));
    leaf.prop_recursive(4, 24, 4, |inner| {
        (
            prop_oneof![
                Just(Op::Union),
                Just(Op::Intersection),
                Just(Op::Difference)
            ],
            prop::collection::vec(inner, 2..4),
        )
            .prop_map(|(op, kids)| Tree::Node(op, kids))
    })
}

fn build(csg: &mut Csg, t: &Tree) -> u32 {
    match t {
        Tree::Leaf(s, m) => {
            let id = csg.prims.len() as u32;
            csg.add_prim(Primitive::new(s.clone(), Transform::new(*m).unwrap(), id))
        }
        Tree::Node(op, kids) => {
            let ids = kids.iter().map(|k| build(csg, k)).collect();
            csg.add_op(*op, ids)
        }
    }
}

fn arb_ray() -> impl Strategy<Value = Ray> {
    (
        prop::array::uniform3(-4.0..4.0f64),
        prop::array::uniform3(-1.0..1.0f64),
    )
        .prop_filter("a direction", |(_, d)| DVec3::from(*d).length() > 1e-3)
        .prop_map(|(o, d)| Ray::new(o.into(), DVec3::from(d).normalize()))
}

/// Every solid of these trees lies within this distance of the origin
/// (translations up to 1.5 in each axis, scales up to 2, a torus's 1.7),
/// and every ray starts within 4√3 of it: t in ±GRID_REACH covers all.
const GRID_REACH: f64 = 16.0;
/// Grid points along the line: a step of 0.005.
const GRID_POINTS: usize = 6400;

/// Spans along `ray` agree with point classification at every point of a
/// grid along the line that is not within 1e-9 of a reported boundary,
/// and between every two consecutive boundaries (and beyond both ends).
fn check_classification(csg: &Csg, root: u32, ray: &Ray) -> Result<(), TestCaseError> {
    let mut st = Stats::default();
    let list = csg.spans(root, ray, f64::NEG_INFINITY, f64::INFINITY, &mut st);
    for s in &list {
        prop_assert!(s.enter.t < s.exit.t);
    }
    for w in list.windows(2) {
        prop_assert!(w[0].exit.t < w[1].enter.t);
    }
    let mut ts: Vec<f64> = list
        .iter()
        .flat_map(|s| [s.enter.t, s.exit.t])
        .filter(|t| t.is_finite())
        .collect();
    // The grid does not know where the spans are: a span csgrt drops
    // (a sphere's rim, a thin shell) still holds grid points that the
    // inside test puts in the solid. Its phase moves with the ray.
    let phase = (ray.origin.x * 7.31 + ray.dir.y * 3.17).rem_euclid(1.0);
    let step = 2.0 * GRID_REACH / GRID_POINTS as f64;
    for k in 0..GRID_POINTS {
        let t = -GRID_REACH + (k as f64 + phase) * step;
        if ts.iter().any(|b| (b - t).abs() < 1e-9) {
            continue;
        }
        prop_assert_eq!(
            contains(&list, t),
            csg.contains(root, ray.at(t)),
            "grid point t = {} on {:?}",
            t,
            ray
        );
    }
    ts.insert(0, -20.0);
    ts.push(20.0);
    for w in ts.windows(2) {
        if w[1] - w[0] < 1e-6 {
            continue;
        }
        for f in [0.5, 0.25, 0.75] {
            let t = w[0] + f * (w[1] - w[0]);
            prop_assert_eq!(
                contains(&list, t),
                csg.contains(root, ray.at(t)),
                "t = {} on {:?}",
                t,
                ray
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn spans_agree_with_point_classification(tree in arb_tree(), rays in prop::collection::vec(arb_ray(), 8)) {
        let mut csg = Csg::default();
        let root = build(&mut csg, &tree);
        csg.root = Some(root);
        for ray in rays {
            check_classification(&csg, root, &ray)?;
        }
    }

    /// A range-restricted query agrees with the full-line one inside the range.
    #[test]
    fn range_restricted_spans_agree_inside_the_range(tree in arb_tree(), ray in arb_ray(), lo in -5.0..5.0f64, len in 0.0..6.0f64) {
        let mut csg = Csg::default();
        let root = build(&mut csg, &tree);
        let mut st = Stats::default();
        let full = csg.spans(root, &ray, f64::NEG_INFINITY, f64::INFINITY, &mut st);
        let part = csg.spans(root, &ray, lo, lo + len, &mut st);
        for k in 1..64 {
            let t = lo + len * k as f64 / 64.0;
            let near = full.iter().any(|s| (s.enter.t - t).abs() < 1e-9 || (s.exit.t - t).abs() < 1e-9);
            if !near {
                prop_assert_eq!(contains(&full, t), contains(&part, t));
            }
        }
    }
}

fn arb_wide() -> impl Strategy<Value = Tree> {
    let leaf = (arb_shape(), arb_transform()).prop_map(|(s, m)| Tree::Leaf(s, m));
    (
        prop_oneof![Just(Op::Union), Just(Op::Difference)],
        prop::collection::vec(leaf, 9..24),
    )
        .prop_map(|(op, kids)| Tree::Node(op, kids))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Wide unions and differences go through a bounding volume hierarchy;
    /// they must classify points exactly as the plain tree does.
    #[test]
    fn wide_nodes_agree_with_point_classification(tree in arb_wide(), rays in prop::collection::vec(arb_ray(), 8)) {
        let mut csg = Csg::default();
        let root = build(&mut csg, &tree);
        for ray in rays {
            check_classification(&csg, root, &ray)?;
        }
    }
}

fn arb_very_wide() -> impl Strategy<Value = Tree> {
    let leaf = (arb_shape(), arb_transform()).prop_map(|(s, m)| Tree::Leaf(s, m));
    prop::collection::vec(leaf, 65..90).prop_map(|kids| Tree::Node(Op::Union, kids))
}

/// The first surface crossing after t = 0 of a full span list.
fn full_first(full: &[Span]) -> Option<f64> {
    full.iter()
        .flat_map(|s| [s.enter, s.exit])
        .find(|b| b.t > 0.0 && b.is_surface())
        .map(|b| b.t)
}

/// What a shadow ray lets through along a list (as the shader reads it):
/// the product of the crossed solids' transmissions, a solid named by the
/// surface the ray enters it by (or leaves by, from inside); here every
/// third primitive is opaque and the others pass a fraction of their own.
fn pass(list: &[Span]) -> f64 {
    let mut pass = 1.0;
    for s in list {
        if s.exit.t <= 0.0 {
            continue;
        }
        let face = if s.enter.t > 0.0 && s.enter.is_surface() {
            s.enter
        } else {
            s.exit
        };
        pass *= kt(face.prim);
        if pass <= 0.0 {
            return 0.0;
        }
    }
    pass
}

fn kt(prim: u32) -> f64 {
    if prim % 3 == 0 {
        0.0
    } else {
        0.5 + prim as f64 / 256.0
    }
}

/// The spans up to and including the first one entered through an opaque
/// surface, as (enter, exit) pairs, that one's exit left out (a solid
/// beyond the stop may extend it).
fn up_to_opaque(list: &[Span]) -> Vec<(f64, Option<f64>)> {
    let mut out = Vec::new();
    for s in list {
        if s.enter.t > 0.0 && s.enter.is_surface() && kt(s.enter.prim) <= 0.0 {
            out.push((s.enter.t, None));
            break;
        }
        out.push((s.enter.t, Some(s.exit.t)));
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]

    /// Two queries stop early in a root union; each must agree with the
    /// full span list, from outside and from inside: the first-hit query
    /// on the first surface, and a shadow ray's list, which stops at the
    /// first opaque surface it enters, on every span up to that one and
    /// on the light let through.
    #[test]
    fn early_stopping_queries_agree_with_the_full_span_list(
        tree in prop_oneof![arb_tree(), arb_wide(), arb_very_wide()],
        rays in prop::collection::vec(arb_ray(), 12),
    ) {
        let mut csg = Csg::default();
        let root = build(&mut csg, &tree);
        csg.root = Some(root);
        for ray in rays {
            let mut st = Stats::default();
            let full = csg.spans(root, &ray, 0.0, f64::INFINITY, &mut st);
            let got = csg.first_boundary(&ray, 0.0, f64::INFINITY, &mut st).map(|b| b.t);
            prop_assert_eq!(got, full_first(&full), "{:?}", ray);
            let opaque = |b: &Boundary| kt(b.prim) <= 0.0;
            let (got, through) = csg.spans_until(&ray, 0.0, f64::INFINITY, &mut st, opaque, |l| {
                (up_to_opaque(l), pass(l))
            });
            prop_assert_eq!(got, up_to_opaque(&full), "{:?}", ray);
            prop_assert_eq!(through, pass(&full), "{:?}", ray);
        }
    }
}
