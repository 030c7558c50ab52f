// Offsets csgrt has no exact form of, of shapes flattened to straight
// polygons and circles (the certified approximation): an ellipse grown
// round, a square less an ellipse grown sharp, a hull of ellipses shrunk.
$fn = 128;
linear_extrude(height = 2) offset(r = 1.5) scale([2, 1]) circle(r = 5);
translate([24, -10]) linear_extrude(height = 2) offset(delta = 1) difference() {
    square(20);
    translate([10, 10]) scale([1, 0.5]) circle(r = 6);
}
translate([0, 16]) linear_extrude(height = 2) offset(r = -1) hull() {
    circle(r = 3);
    translate([10, 0]) scale([1, 2]) circle(r = 3);
}
