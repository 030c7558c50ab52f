// Hulls and sums of combinations with turned solids, cut into convex
// polytopes: a torus less a box, hulled; a turned profile with a slot,
// rounded by a ball; a part turn (its wedge made of halfspaces) met with
// a ball, hulled.
$fn = 48;
hull() difference() {
    rotate_extrude() translate([10, 0]) circle(r = 2);
    translate([0, 0, -5]) cube(20);
}
translate([30, 0, 0]) minkowski() {
    difference() {
        rotate_extrude() polygon([[3, 0], [8, 0], [8, 2], [5, 4], [3, 4]]);
        translate([-10, -1, -1]) cube([20, 2, 10]);
    }
    sphere(r = 0.5);
}
translate([0, 30, 0]) hull() intersection() {
    rotate_extrude(angle = 120) translate([6, 0]) square([3, 5]);
    sphere(r = 8);
}
