$fn = 16;
rotate_extrude() translate([4, 0]) square([1.5, 3], center = true);
