$fn = 24;
difference() { sphere(r = 5); cube(6, center = true); translate([0, 0, 3]) cylinder(r = 2, h = 5); }
