// The shadows (projection, cut = false) of a ball with a tapered hole
// and of a box cut by a box, extruded.
$fn = 48;
linear_extrude(2) projection() difference() {
    sphere(r = 12);
    rotate([0, 30, 0]) cylinder(r1 = 6, r2 = 3, h = 40, center = true);
}
translate([25, 0, 0]) linear_extrude(3) projection() difference() {
    rotate([20, 10, 0]) cube(15, center = true);
    cube([4, 30, 30], center = true);
}
translate([0, 25, 0]) linear_extrude(1) projection() difference() {
    cylinder(r = 10, h = 4);
    translate([0, 0, -1]) cylinder(r = 5, h = 6);
}
