// Polyhedra that are not convex, hulled in a difference and summed: csgrt
// cuts each exactly into the convex cells of its faces' planes.
module ell(a, b, h) polyhedron(
    points = [[0, 0, 0], [a, 0, 0], [a, b, 0], [b, b, 0], [b, a, 0], [0, a, 0],
              [0, 0, h], [a, 0, h], [a, b, h], [b, b, h], [b, a, h], [0, a, h]],
    faces = [[0, 1, 2, 3, 4, 5], [11, 10, 9, 8, 7, 6], [0, 6, 7, 1], [1, 7, 8, 2],
             [2, 8, 9, 3], [3, 9, 10, 4], [4, 10, 11, 5], [5, 11, 6, 0]]);
hull() difference() {
    ell(10, 3, 4);
    translate([7, -1, -1]) cube([5, 2.5, 6]);
    translate([-1, -1, 2]) rotate([0, 0, 45]) cube([3, 3, 3]);
}
translate([20, 0, 0]) minkowski() {
    ell(8, 2, 2);
    rotate([30, 20, 10]) ell(4, 1.5, 1);
}
