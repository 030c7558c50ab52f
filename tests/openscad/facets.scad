difference() { cylinder(h = 4, r = 5, $fn = 6); translate([0,0,-1]) cylinder(h = 6, r = 2.5, $fn = 8); }
translate([12, 0, 0]) cylinder(h = 6, r1 = 4, r2 = 1, $fn = 5);
translate([-12, 0, 0]) cylinder(h = 6, r1 = 0, r2 = 4, center = true, $fn = 3);
translate([0, 12, 0]) cylinder(h = 3, d1 = 3, d2 = 7, $fn = 4);
translate([0, -12, 0]) cylinder(h = 3, r = 3, $fn = 2);
