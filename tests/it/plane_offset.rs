//! OpenSCAD's 2-D `offset` (`plane::offset`) against closed forms, in the
//! manner of manifold's offset corpus: convex and concave outlines, a hole,
//! a sharp corner and circles, grown and shrunk, round and mitred. Each
//! result is read by the test's own inside test and compared with the
//! exact region's signed distance over a grid, away from its boundary.

use crate::common::{agree_on_grid, box_distance, figure_contains, polygon, L_CORNERS};
use csgrt::plane::figure::Figure;
use csgrt::plane::offset::{offset, Join};
use glam::DVec2;

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn grown(f: Figure, join: Join, d: f64) -> Figure {
    offset(f, join, d)
        .expect("offset")
        .expect("a non-empty offset")
}

fn l_shape() -> Figure {
    polygon(&L_CORNERS)
}

/// The union's signed distance: exact outside, a bound of the right sign
/// inside (so the grid's margin only skips more).
fn l_distance(p: DVec2) -> f64 {
    box_distance(p, v(0.0, 0.0), v(2.0, 1.0)).min(box_distance(p, v(0.0, 0.0), v(1.0, 2.0)))
}

const MARGIN: f64 = 1e-9;

#[test]
fn a_square_grown_round_is_the_rounded_square() {
    let sq = polygon(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]);
    let f = grown(sq, Join::Round, 0.3);
    let n = agree_on_grid(
        "square round +0.3",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| box_distance(p, v(0.0, 0.0), v(2.0, 2.0)) - 0.3,
    );
    assert!(n > 35_000);
}

#[test]
fn a_square_grown_by_delta_keeps_its_corners() {
    let sq = polygon(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]);
    let f = grown(sq, Join::Miter, 0.3);
    agree_on_grid(
        "square delta +0.3",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| box_distance(p, v(-0.3, -0.3), v(2.3, 2.3)),
    );
}

#[test]
fn a_square_shrunk_round_is_a_smaller_square() {
    // Eroded by a disc, a convex polygon keeps sharp corners.
    let sq = polygon(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]);
    let f = grown(sq, Join::Round, -0.3);
    agree_on_grid(
        "square round -0.3",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| box_distance(p, v(0.3, 0.3), v(1.7, 1.7)),
    );
}

#[test]
fn a_concave_outline_grown_round() {
    let f = grown(l_shape(), Join::Round, 0.25);
    agree_on_grid(
        "L round +0.25",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| l_distance(p) - 0.25,
    );
}

#[test]
fn a_concave_outline_shrunk_by_delta() {
    // Each edge moved in by 0.2 with mitred corners: the L eroded by the
    // square of half-side 0.2, the two boxes each shrunk.
    let f = grown(l_shape(), Join::Miter, -0.2);
    agree_on_grid(
        "L delta -0.2",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| {
            box_distance(p, v(0.2, 0.2), v(1.8, 0.8)).min(box_distance(p, v(0.2, 0.2), v(0.8, 1.8)))
        },
    );
}

#[test]
fn a_frame_grown_round_closes_in_on_its_hole() {
    let frame = Figure::Polygon(csgrt::plane::Outlines::polygons(vec![
        vec![v(0.0, 0.0), v(3.0, 0.0), v(3.0, 3.0), v(0.0, 3.0)],
        vec![v(1.0, 1.0), v(2.0, 1.0), v(2.0, 2.0), v(1.0, 2.0)],
    ]));
    let f = grown(frame, Join::Round, 0.2);
    agree_on_grid(
        "frame round +0.2",
        v(-1.0, -1.0),
        v(4.0, 4.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| {
            let outer = box_distance(p, v(0.0, 0.0), v(3.0, 3.0));
            let hole = box_distance(p, v(1.0, 1.0), v(2.0, 2.0));
            outer.max(-hole) - 0.2
        },
    );
}

#[test]
fn a_sharp_corner_grown_by_delta_is_mitred() {
    // A triangle with a 14° corner: each edge moved out by 0.1, the corner
    // mitred (OpenSCAD's miter limit of 10⁶ keeps it).
    let pts = [v(0.0, 0.0), v(4.0, 0.0), v(0.0, 1.0)];
    let tri = polygon(&[(0.0, 0.0), (4.0, 0.0), (0.0, 1.0)]);
    let f = grown(tri, Join::Miter, 0.1);
    agree_on_grid(
        "triangle delta +0.1",
        v(-1.0, -1.0),
        v(6.0, 2.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| {
            (0..3)
                .map(|i| {
                    let (a, b) = (pts[i], pts[(i + 1) % 3]);
                    let n = DVec2::new(b.y - a.y, a.x - b.x).normalize();
                    n.dot(p - a) - 0.1
                })
                .fold(f64::NEG_INFINITY, f64::max)
        },
    );
}

#[test]
fn circles_grow_and_shrink_as_circles_and_vanish() {
    let c = v(0.5, -0.25);
    for (d, r) in [(0.4, 1.4), (-0.4, 0.6)] {
        let f = grown(Figure::disc(c, 1.0), Join::Round, d);
        agree_on_grid(
            "disc",
            v(-2.0, -2.0),
            v(2.0, 2.0),
            MARGIN,
            |p| figure_contains(&f, p),
            |p| (p - c).length() - r,
        );
    }
    assert!(offset(Figure::disc(c, 1.0), Join::Round, -1.5)
        .expect("offset")
        .is_none());
}
