//! OpenSCAD's 2-D `minkowski()` (`plane::sum`) against closed forms: a box
//! plus a disc or a box, a concave outline plus a box or a disc, convex
//! polygons (against the hull of every pair's sum, found here by brute
//! force) and discs.

use crate::common::{
    agree_on_grid, box_distance, figure_contains, polygon, support_distance, support_margin,
    L_CORNERS,
};
use csgrt::plane::figure::Figure;
use csgrt::plane::sum::minkowski;
use glam::DVec2;

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn sum(ops: Vec<Figure>) -> Figure {
    minkowski(ops).expect("summed").expect("not empty")
}

fn square(lo: f64, hi: f64) -> Figure {
    polygon(&[(lo, lo), (hi, lo), (hi, hi), (lo, hi)])
}

fn l_shape() -> Figure {
    polygon(&L_CORNERS)
}

/// The signed distance to the L grown by the box of half-side h: the two
/// boxes each grown (exact outside, of the right sign inside).
fn l_grown(p: DVec2, h: f64) -> f64 {
    box_distance(p, v(-h, -h), v(2.0 + h, 1.0 + h)).min(box_distance(
        p,
        v(-h, -h),
        v(1.0 + h, 2.0 + h),
    ))
}

const MARGIN: f64 = 1e-9;

#[test]
fn a_box_plus_a_disc_is_the_rounded_box() {
    let f = sum(vec![square(0.0, 2.0), Figure::disc(v(0.5, 0.25), 0.3)]);
    let n = agree_on_grid(
        "box + disc",
        v(-1.0, -1.0),
        v(3.5, 3.5),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| box_distance(p - v(0.5, 0.25), v(0.0, 0.0), v(2.0, 2.0)) - 0.3,
    );
    assert!(n > 35_000);
}

#[test]
fn two_boxes_sum_to_a_box() {
    let f = sum(vec![square(0.0, 2.0), square(-0.5, 0.5)]);
    agree_on_grid(
        "box + box",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| box_distance(p, v(-0.5, -0.5), v(2.5, 2.5)),
    );
}

#[test]
fn a_concave_outline_plus_a_box() {
    let f = sum(vec![l_shape(), square(-0.2, 0.2)]);
    agree_on_grid(
        "L + box",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| l_grown(p, 0.2),
    );
}

#[test]
fn a_concave_outline_plus_a_disc_is_its_round_offset() {
    let f = sum(vec![l_shape(), Figure::disc(DVec2::ZERO, 0.25)]);
    agree_on_grid(
        "L + disc",
        v(-1.0, -1.0),
        v(3.0, 3.0),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| l_grown(p, 0.0) - 0.25,
    );
}

#[test]
fn convex_polygons_sum_to_the_hull_of_their_corners_sums() {
    let a = [v(0.0, 0.0), v(2.0, 0.3), v(0.4, 1.5)];
    let b = [v(-0.3, -0.2), v(0.5, -0.1), v(0.6, 0.7), v(-0.2, 0.4)];
    let tuple = |p: &[DVec2]| p.iter().map(|q| (q.x, q.y)).collect::<Vec<_>>();
    let f = sum(vec![polygon(&tuple(&a)), polygon(&tuple(&b))]);
    let sums: Vec<DVec2> = a
        .iter()
        .flat_map(|&p| b.iter().map(move |&q| p + q))
        .collect();
    agree_on_grid(
        "triangle + quadrilateral",
        v(-1.0, -1.0),
        v(3.5, 3.0),
        support_margin(),
        |p| figure_contains(&f, p),
        |p| {
            support_distance(p, |u| {
                sums.iter().map(|s| s.dot(u)).fold(f64::MIN, f64::max)
            })
        },
    );
}

#[test]
fn discs_sum_to_a_disc() {
    let f = sum(vec![
        Figure::disc(v(1.0, 0.0), 0.5),
        Figure::disc(v(-0.25, 0.5), 0.7),
    ]);
    agree_on_grid(
        "disc + disc",
        v(-2.0, -2.0),
        v(2.5, 2.5),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| (p - v(0.75, 0.5)).length() - 1.2,
    );
}

#[test]
fn a_circle_inside_a_union_operand_is_summed_too() {
    // (box ∪ disc) ⊕ disc = (box ⊕ disc) ∪ (disc grown by the radius):
    // the union's circle summed with the other disc's centre is one point,
    // and its piece must stay the grown disc (found by OpenSCAD's own sums,
    // tools/oracle/offset_vs_openscad.py --kind sum).
    use csgrt::math::boolean::Op;
    let union = Figure::Op(
        Op::Union,
        vec![square(0.0, 1.0), Figure::disc(v(3.0, 0.5), 1.0)],
    );
    let f = sum(vec![union, Figure::disc(v(0.0, 0.0), 0.5)]);
    agree_on_grid(
        "(box + disc) + disc",
        v(-1.0, -1.5),
        v(5.0, 2.5),
        MARGIN,
        |p| figure_contains(&f, p),
        |p| box_distance(p, v(0.0, 0.0), v(1.0, 1.0)).min((p - v(3.0, 0.5)).length() - 1.0) - 0.5,
    );
}
