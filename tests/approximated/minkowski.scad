// A plate with a square and a round hole, rounded by a ball: csgrt cuts
// the plate into convex polytopes and sums each with the ball.
$fn = 48;
minkowski() {
    difference() {
        cube([30, 20, 4]);
        translate([5, 5, -1]) cube([6, 6, 6]);
        translate([20, 10, -1]) cylinder(r = 4, h = 6);
    }
    sphere(r = 1.5);
}
