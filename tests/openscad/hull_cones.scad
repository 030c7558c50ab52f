// Hulls of cylinders and cones with parallel axes whose discs are one disc
// scaled: the hull of their centres, the frustum swept between each pair
// of discs on its boundary, and a wedge under each plane that touches
// three. (Their sweeps rise at least as far as they run: the oracle's
// faceting bound holds there; tools/oracle/accuracy.py's chamfered_plate
// checks a shallow chamfer exactly.)
$fn = 64;
// A rounded plate under a smaller rounded top: a chamfer.
hull() {
    linear_extrude(4) offset(r = 3) square([20, 14], center = true);
    translate([0, 0, 11]) linear_extrude(0.5) offset(r = 1.5) square([12, 8], center = true);
}
// A stand: a cone, an upturned cone and a cylinder at three places.
translate([30, 0, 0]) hull() {
    cylinder(r1 = 6, r2 = 3, h = 5);
    translate([4, 3, 12]) cylinder(r1 = 1, r2 = 4, h = 3);
    translate([-3, 6, 2]) cylinder(r = 2, h = 24);
}
// A cone and a cylinder, stretched: the discs are ellipses.
translate([0, 30, 0]) scale([1, 0.6, 1]) hull() {
    cylinder(r1 = 5, r2 = 0, h = 12);
    translate([5, 3, 6]) cylinder(r = 2.5, h = 5);
}
// Tilted: three cones and a box inside their hull.
translate([30, 30, 4]) rotate([25, -30, 15]) hull() {
    cylinder(r1 = 3, r2 = 1, h = 10);
    translate([3, 0, 14]) cylinder(r = 2, h = 2);
    translate([0, 4, -10]) cylinder(r1 = 0.5, r2 = 2.5, h = 3);
    translate([0, 0, 4]) cube(1, center = true);
}
// A box plus a frustum.
translate([60, 0, 0]) minkowski() {
    cube([10, 6, 8]);
    cylinder(r1 = 2, r2 = 1, h = 2);
}
