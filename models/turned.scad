// A turned part: a knob's profile (a polygon turned, with a bead: a circle
// turned to a torus), a hexagon nut ($fn = 6), a twisted grip and a cut
// quarter showing the inside (rotate_extrude, linear_extrude with twist).
difference() {
    union() {
        rotate_extrude()
            polygon([[0, 0], [14, 0], [14, 3], [10, 5], [8, 12], [9, 20], [12, 24], [11, 28], [0, 28]]);
        translate([0, 0, 24]) rotate_extrude() translate([12, 0]) circle(r = 2);
    }
    translate([0, 0, -1]) cylinder(h = 10, r = 4, $fn = 6);
    translate([0, 0, 14]) cube([20, 20, 20]);
}
translate([34, 0, 0]) difference() {
    cylinder(h = 8, r = 10, $fn = 6);
    translate([0, 0, -1]) cylinder(h = 10, r = 5);
}
translate([-34, 0, 0]) linear_extrude(height = 30, twist = -120, slices = 60)
    difference() {
        polygon([for (i = [0:11]) let(a = i * 30, r = i % 2 ? 5 : 8) [r * cos(a), r * sin(a)]]);
        circle(r = 2.5);
    }
