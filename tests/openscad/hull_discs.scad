// Hulls of cylinders whose discs are one disc moved, and polytopes plus
// such a cylinder: a polytope P plus a flat disc E, written out as P with
// its faces pushed out across E's plane and a cylinder swept along each
// edge of P that is not parallel to that plane.
$fn = 64;
// A tapered rounded box: rounded rectangles at two heights (the
// rectangles' pieces inside the hull of the corners' cylinders).
hull() {
    linear_extrude(0.01) offset(r = 2.5) square([20, 14], center = true);
    translate([0, 0, 6]) linear_extrude(0.01) offset(r = 2.5) square([12, 8], center = true);
}
// OpenSCAD's rounded box.
translate([30, 0, 0]) minkowski() {
    cube([12, 8, 3], center = true);
    cylinder(r = 2, h = 1);
}
// Elliptic discs at three heights: one disc, stretched.
translate([0, 30, 0]) scale([1, 0.6, 1]) hull() {
    cylinder(r = 5, h = 1);
    translate([8, 4, 6]) cylinder(r = 5, h = 2);
    translate([-3, 10, 3]) cylinder(r = 5, h = 1);
}
// Tilted, at four heights. (Along an edge that is near the discs' plane
// the sweep's normal turns by up to |edge| / |its rise| times the angle
// its circle turns, and so does the faceted mesh's error in the normal:
// the edges here rise at least as far as they run, within what the oracle's
// bound allows; tools/oracle/accuracy.py's lofted_plate checks shallow
// ones exactly.)
translate([30, 30, 4]) rotate([20, 35, 10]) hull() {
    for (p = [[0, 0, 0], [6, 0, 8], [0, 5, 16], [6, 6, -9]])
        translate(p) cylinder(r = 1.5, h = 2);
}
// Discs along x at four heights and depths: the faces on each side have
// one horizontal direction (creases between them), and a ridge at the top
// and bottom.
translate([0, 60, 0]) hull() {
    for (x = [0, 10], p = [[0, 0], [3, 4], [0, 8], [-4, 4]])
        translate([x, p[0], p[1]]) cylinder(r = 2, h = 0.5);
}
// Discs in one upright plane: a slab across them and its rim's cylinders.
translate([-25, 60, 0]) hull() {
    for (p = [[0, 0], [12, 1], [4, 9]]) translate([p[0], 0, p[1]]) cylinder(r = 2, h = 0.5);
}
// A flat polytope plus a disc: a tilted square swept across the disc.
translate([30, 60, 0]) minkowski() {
    rotate([0, 40, 0]) cube([8, 8, 0.001]);
    scale([1, 2, 1]) cylinder(r = 1.5, h = 0.5);
}
