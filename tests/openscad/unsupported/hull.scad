hull() { cube(2); translate([5, 0, 0]) sphere(1); }
