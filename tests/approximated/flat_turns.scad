// Turns and twists csgrt has no exact form of, flattened to straight
// polygons (the certified approximation): a slanted ellipse that reaches
// the axis, a circle centred left of the axis that crosses it (the lemon
// of its part at x >= 0), a twisted hull of ellipses.
$fn = 128;
rotate_extrude() difference() {
    rotate(30) scale([3, 1]) circle(r = 4);
    translate([-20, -20]) square([20, 40]);
}
translate([30, 0, 0]) rotate_extrude() difference() {
    translate([-2, 0]) circle(r = 6);
    translate([-20, -20]) square([20, 40]);
}
translate([0, 30, 0]) linear_extrude(height = 10, twist = 90) hull() {
    translate([5, 0]) scale([1, 2]) circle(r = 2);
    translate([-3, 2]) scale([2, 1]) circle(r = 3);
}
translate([30, 30, 0]) rotate_extrude(angle = 270) hull() {
    translate([6, 0]) scale([1, 2]) circle(r = 2);
    translate([10, 3]) circle(r = 1);
}
