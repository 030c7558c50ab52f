// Text turned about the axis: a full turn, a partial one, and one mirrored
// to the other side of the axis.
rotate_extrude() translate([6, 0]) text("Sg", size = 8);
translate([30, 0, 0]) rotate_extrude(angle = 230) translate([4, -4]) text("e", size = 10, font = "Liberation Sans:style=Bold");
translate([0, 30, 0]) rotate_extrude() mirror([1, 0]) translate([3, 0]) text("o", size = 9);
