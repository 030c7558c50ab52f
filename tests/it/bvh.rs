//! The hierarchy over boxed ids, at every leaf size: against brute force.

use csgrt::geometry::bvh::Bvh;
use csgrt::geometry::{Aabb, Ray};
use csgrt::stats::Stats;
use glam::DVec3;
use proptest::prelude::*;

fn arb_boxes() -> impl Strategy<Value = Vec<(u32, Aabb)>> {
    prop::collection::vec(
        (
            prop::array::uniform3(-10.0..10.0f64),
            prop::array::uniform3(0.01..3.0f64),
        ),
        1..120,
    )
    .prop_map(|v| {
        v.into_iter()
            .enumerate()
            .map(|(i, (lo, size))| {
                let lo = DVec3::from(lo);
                (i as u32, Aabb::new(lo, lo + DVec3::from(size)))
            })
            .collect()
    })
}

fn arb_ray() -> impl Strategy<Value = Ray> {
    (
        prop::array::uniform3(-15.0..15.0f64),
        prop::array::uniform3(-1.0..1.0f64),
    )
        .prop_filter("a direction", |(_, d)| DVec3::from(*d).length() > 1e-3)
        .prop_map(|(o, d)| Ray::new(o.into(), DVec3::from(d).normalize()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// `visit` reaches every item whose box the ray meets (and, through
    /// their leaves, maybe a few others), each once; `visit_near_first`
    /// with no cut visits exactly the items whose own boxes the ray meets,
    /// and with the cut at the first entry, every item whose box begins
    /// by then.
    #[test]
    fn every_leaf_size_finds_what_brute_force_finds(
        items in arb_boxes(),
        ray in arb_ray(),
        leaf in prop_oneof![Just(1usize), Just(2), Just(3), Just(4), Just(8)],
    ) {
        let bvh = Bvh::build(&items, leaf);
        let mut st = Stats::default();
        let want: Vec<u32> = items
            .iter()
            .filter(|(_, b)| b.hit(&ray, 0.0, f64::INFINITY))
            .map(|(id, _)| *id)
            .collect();

        let mut seen = Vec::new();
        bvh.visit(&ray, 0.0, f64::INFINITY, &mut st, |id| seen.push(id));
        let mut sorted = seen.clone();
        sorted.sort_unstable();
        sorted.dedup();
        prop_assert_eq!(sorted.len(), seen.len(), "an item visited twice");
        for id in &want {
            prop_assert!(seen.contains(id), "leaf {}: item {} missed", leaf, id);
        }

        let mut near = Vec::new();
        bvh.visit_near_first(&ray, 0.0, f64::INFINITY, &mut st, |id, _| {
            near.push(id);
            f64::INFINITY
        });
        near.sort_unstable();
        prop_assert_eq!(&near, &want, "leaf {}", leaf);

        // With the cut at the nearest entry of all, every item whose box
        // begins there is visited, whatever else is.
        let entry = |id: u32| items[id as usize].1.entry(&ray, 0.0, f64::INFINITY);
        if let Some(first) = want.iter().filter_map(|&id| entry(id)).reduce(f64::min) {
            let mut cut_seen = Vec::new();
            bvh.visit_near_first(&ray, 0.0, f64::INFINITY, &mut st, |id, _| {
                cut_seen.push(id);
                first
            });
            for &id in &want {
                if entry(id).unwrap() <= first {
                    prop_assert!(cut_seen.contains(&id), "leaf {}: item {} at the cut missed", leaf, id);
                }
            }
        }
    }
}
