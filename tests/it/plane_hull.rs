//! Hulls in the plane (`plane::hull`), in the manner of manifold's
//! `hull_test.cpp`: random points, points on the hull's edges, repeats and
//! collinear points; hulls of discs against their support functions.

use crate::common::{agree_on_grid, even_odd, support_distance, support_margin, Rng};
use csgrt::plane::hull::{convex_polygon, disc_hull, hull_indices_2d};
use glam::DVec2;

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

/// Whether p is left of (or on) the edge a → b.
fn left_of(a: DVec2, b: DVec2, p: DVec2) -> bool {
    (b - a).perp_dot(p - a) >= -1e-12 * (b - a).length()
}

#[test]
fn random_points_lie_in_their_hull_whose_corners_are_all_needed() {
    let mut rng = Rng(5);
    for round in 0..50 {
        let n = 3 + round % 40;
        let pts: Vec<DVec2> = (0..n)
            .map(|_| v(rng.range(-3.0, 3.0), rng.range(-1.0, 2.0)))
            .collect();
        let idx = hull_indices_2d(&pts, 0.0);
        let hull: Vec<DVec2> = idx.iter().map(|&i| pts[i]).collect();
        let m = hull.len();
        assert!(m >= 3, "round {round}: {m} corners");
        // Counter-clockwise and convex.
        assert!(convex_polygon(&hull));
        let area: f64 = (0..m).map(|i| hull[i].perp_dot(hull[(i + 1) % m])).sum();
        assert!(area > 0.0, "round {round}: clockwise");
        // Every point inside or on it.
        for p in &pts {
            assert!(
                (0..m).all(|i| left_of(hull[i], hull[(i + 1) % m], *p)),
                "round {round}: {p:?} outside the hull"
            );
        }
        // Every corner needed: outside the polygon of the others.
        for k in 0..m {
            let rest: Vec<DVec2> = (0..m).filter(|&i| i != k).map(|i| hull[i]).collect();
            let r = rest.len();
            assert!(
                (0..r).any(|i| !left_of(rest[i], rest[(i + 1) % r], hull[k])),
                "round {round}: corner {k} is not needed"
            );
        }
    }
}

#[test]
fn points_on_edges_repeats_and_collinear_points() {
    // A 5×5 grid: its four corners only.
    let grid: Vec<DVec2> = (0..25).map(|k| v((k % 5) as f64, (k / 5) as f64)).collect();
    let mut corners: Vec<DVec2> = hull_indices_2d(&grid, 0.0)
        .iter()
        .map(|&i| grid[i])
        .collect();
    corners.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    assert_eq!(
        corners,
        vec![v(0.0, 0.0), v(0.0, 4.0), v(4.0, 0.0), v(4.0, 4.0)]
    );
    // A triangle's corners each given three times.
    let tri = [v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)];
    let repeated: Vec<DVec2> = tri.iter().flat_map(|&p| [p, p, p]).collect();
    assert_eq!(hull_indices_2d(&repeated, 0.0).len(), 3);
    // Points on one line: no area, at most its two ends.
    let line: Vec<DVec2> = (0..7).map(|k| v(k as f64 * 0.5, k as f64 * 0.25)).collect();
    let ends = hull_indices_2d(&line, 0.0);
    assert!(ends.len() <= 2, "{ends:?}");
    for i in ends {
        assert!(
            i == 0 || i == 6,
            "an inner point of the line as a corner: {i}"
        );
    }
    // One point.
    assert!(hull_indices_2d(&[v(1.0, 1.0), v(1.0, 1.0)], 0.0).len() <= 1);
}

/// Whether p is in the hull `disc_hull` gives: its polygon, or one of the
/// discs on its boundary.
fn in_disc_hull(poly: &[DVec2], on: &[usize], discs: &[(DVec2, f64)], p: DVec2) -> bool {
    even_odd(&[poly.to_vec()], p) || on.iter().any(|&i| (p - discs[i].0).length() <= discs[i].1)
}

#[test]
fn two_equal_discs_make_a_capsule() {
    let discs = [(v(-1.0, 0.2), 0.5), (v(1.5, -0.3), 0.5)];
    let (poly, on) = disc_hull(&discs).expect("a hull with area");
    let (a, b) = (discs[0].0, discs[1].0);
    agree_on_grid(
        "capsule",
        v(-2.0, -1.5),
        v(2.5, 1.5),
        1e-9,
        |p| in_disc_hull(&poly, &on, &discs, p),
        |p| {
            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            (a + (b - a) * t - p).length() - 0.5
        },
    );
}

#[test]
fn discs_of_different_radii_against_their_support_function() {
    let discs = [
        (v(0.0, 0.0), 0.8),
        (v(2.0, 0.5), 0.3),
        (v(0.5, 1.8), 0.1),
        (v(0.6, 0.4), 0.2), // inside the first: not on the hull
        (v(1.0, 1.0), 0.0), // a point inside
    ];
    let (poly, on) = disc_hull(&discs).expect("a hull with area");
    assert!(!on.contains(&3) && !on.contains(&4), "{on:?}");
    agree_on_grid(
        "three discs",
        v(-1.5, -1.5),
        v(3.0, 3.0),
        support_margin(),
        |p| in_disc_hull(&poly, &on, &discs, p),
        |p| {
            support_distance(p, |u| {
                discs
                    .iter()
                    .map(|(c, r)| c.dot(u) + r)
                    .fold(f64::MIN, f64::max)
            })
        },
    );
    // Centres on one line with equal radii: a capsule's hull still has
    // area; points alone on a line have none.
    assert!(disc_hull(&[(v(0.0, 0.0), 0.0), (v(1.0, 1.0), 0.0), (v(2.0, 2.0), 0.0)]).is_none());
}
