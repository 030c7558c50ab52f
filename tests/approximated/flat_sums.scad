// 2-D Minkowski sums of shapes that are not convex (each flattened to
// straight polygons, but for a circle on its own, and summed exactly):
// an L plus an annulus, a square ring plus a square with a round hole.
$fn = 128;
linear_extrude(height = 2) minkowski() {
    polygon([[0, 0], [20, 0], [20, 5], [5, 5], [5, 20], [0, 20]]);
    difference() {
        circle(r = 5);
        circle(r = 3);
    }
}
translate([32, 0]) linear_extrude(height = 2) minkowski() {
    difference() {
        square([18, 18], center = true);
        square([12, 12], center = true);
    }
    difference() {
        square([8, 8], center = true);
        circle(r = 2);
    }
}
