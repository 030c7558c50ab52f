//! The boundary of a 2-D combination read as pieces (`plane::sites`):
//! outlines of unions, differences and intersections of polygons against
//! the combination itself, and the hull of a combination with circles
//! against its support function.

use crate::common::{
    agree_on_grid, box_distance, even_odd, figure_contains, polygon, support_distance,
    support_margin,
};
use csgrt::math::boolean::Op;
use csgrt::plane::figure::Figure;
use csgrt::plane::hull::arc_hull;
use csgrt::plane::sites::{outline, sites, Site};
use glam::DVec2;

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Figure {
    polygon(&[(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
}

/// The outline's loops, filled even-odd, against the figure read by the
/// set operations; the number of loops and corners it has.
fn outline_agrees(what: &str, f: &Figure, loops: usize, corners: usize) {
    let o = outline(f).unwrap_or_else(|| panic!("{what}: no outline"));
    assert_eq!(o.loops.len(), loops, "{what}: loops");
    assert_eq!(
        o.loops.iter().map(Vec::len).sum::<usize>(),
        corners,
        "{what}: corners"
    );
    // The distance to the nearest edge of either reading, for the margin.
    let edges: Vec<(DVec2, DVec2)> = o
        .loops
        .iter()
        .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
        .collect();
    agree_on_grid(
        what,
        v(-1.0, -1.0),
        v(4.0, 4.0),
        1e-6,
        |p| even_odd(&o.loops, p),
        |p| {
            let d = edges
                .iter()
                .map(|&(a, b)| {
                    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    (a + (b - a) * t - p).length()
                })
                .fold(f64::INFINITY, f64::min);
            if figure_contains(f, p) {
                -d
            } else {
                d
            }
        },
    );
}

#[test]
fn the_outline_of_two_overlapping_boxes() {
    let f = Figure::Op(
        Op::Union,
        vec![rect(0.0, 0.0, 2.0, 1.0), rect(1.0, 0.5, 3.0, 3.0)],
    );
    outline_agrees("union", &f, 1, 8);
}

#[test]
fn the_outline_of_a_box_with_a_hole_and_a_notch() {
    let hole = Figure::Op(
        Op::Difference,
        vec![rect(0.0, 0.0, 3.0, 3.0), rect(1.0, 1.0, 2.0, 2.0)],
    );
    outline_agrees("hole", &hole, 2, 8);
    // Cut at an edge: the notch shares the outline's own line.
    let notch = Figure::Op(
        Op::Difference,
        vec![rect(0.0, 0.0, 3.0, 3.0), rect(1.0, 2.0, 2.0, 3.0)],
    );
    outline_agrees("notch", &notch, 1, 8);
}

#[test]
fn the_outline_of_an_intersection() {
    let f = Figure::Op(
        Op::Intersection,
        vec![rect(0.0, 0.0, 2.0, 2.0), rect(1.0, 0.5, 3.0, 3.0)],
    );
    outline_agrees("intersection", &f, 1, 4);
    // The same region by the test's own box: [1,2]×[0.5,2].
    let o = outline(&f).unwrap();
    agree_on_grid(
        "intersection box",
        v(-1.0, -1.0),
        v(4.0, 4.0),
        1e-9,
        |p| even_odd(&o.loops, p),
        |p| box_distance(p, v(1.0, 0.5), v(2.0, 2.0)),
    );
}

#[test]
fn the_hull_of_a_box_and_a_disc() {
    // A box and a disc reaching past its corner: the hull follows the
    // disc's arc and the box's far corners.
    let (c, r) = (v(2.2, 1.8), 0.6);
    let f = Figure::Op(
        Op::Union,
        vec![rect(0.0, 0.0, 2.0, 1.0), Figure::disc(c, r)],
    );
    let mut found: Vec<Site> = Vec::new();
    assert!(sites(&f, &mut found));
    let (poly, on) = arc_hull(&found).expect("a hull with area");
    // OpenSCAD's hull() of the same figure, as the kernel builds it.
    let hulled = csgrt::plane::hull::hull_of_figures(vec![f.clone()]);
    let inside = |p: DVec2| {
        assert_eq!(
            figure_contains(&hulled, p),
            even_odd(std::slice::from_ref(&poly), p)
                || on.iter().any(|&i| (p - found[i].c).length() <= found[i].r),
            "hull_of_figures at {p:?}"
        );
        even_odd(std::slice::from_ref(&poly), p)
            || on.iter().any(|&i| (p - found[i].c).length() <= found[i].r)
    };
    let corners = [v(0.0, 0.0), v(2.0, 0.0), v(2.0, 1.0), v(0.0, 1.0)];
    agree_on_grid(
        "hull of box and disc",
        v(-1.0, -1.0),
        v(3.5, 3.0),
        support_margin(),
        inside,
        |p| {
            support_distance(p, |u| {
                corners
                    .iter()
                    .map(|q| q.dot(u))
                    .fold(c.dot(u) + r, f64::max)
            })
        },
    );
}
