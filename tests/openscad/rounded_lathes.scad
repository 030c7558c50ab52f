// Cylinders and cones plus a ball: a turned set whose profile is the
// frustums' hull offset by the ball's radius (a lathe of the pushed edges,
// a torus about each rim, a ball at an apex); and sets rotated by
// OpenSCAD's export, whose matrices are square to about 1e-6 only.
// oracle: at most 128 segments
$fn = 64;
minkowski() { cylinder(r = 5, h = 8); sphere(r = 1.5); }
translate([16, 0, 0]) minkowski() { cylinder(r1 = 5, r2 = 2, h = 8); sphere(r = 1); }
translate([0, 16, 0]) minkowski() {
    cylinder(r1 = 0, r2 = 4, h = 6);
    translate([1, 2, 3]) sphere(r = 1.2);
}
translate([16, 16, 2]) minkowski() {
    rotate([40, 20, 0]) hull() {
        cylinder(r = 3, h = 2);
        translate([0, 0, 4]) cylinder(r1 = 2, r2 = 0.5, h = 3);
    }
    sphere(r = 0.8);
}
// Balls of one radius turned about z (the export's matrices): a rounded
// trapezohedron.
translate([32, 8, 4]) hull() {
    for (i = [0:9]) rotate([0, 0, 36 * i]) translate([6, 0, i % 2 ? 1.3 : -1.3]) sphere(r = 1.5);
}
