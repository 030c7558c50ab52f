rotate_extrude() translate([5, 0]) circle(1);
// Across the axis: OpenSCAD's error, and the rest renders without it.
translate([0, 12, 0]) rotate_extrude() translate([-1, 0]) square(3);
