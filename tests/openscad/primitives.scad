// Every OpenSCAD 3-D primitive form csgrt renders.
$fn = 48;
cube(10);
translate([15, 0, 0]) cube([4, 8, 12], center = true);
translate([30, 0, 5]) sphere(r = 5);
translate([45, 0, 5]) sphere(d = 8, $fa = 5, $fs = 0.5);
translate([0, 20, 0]) cylinder(h = 10, r = 4);
translate([15, 20, 0]) cylinder(h = 10, r1 = 5, r2 = 0);
translate([30, 20, 5]) cylinder(h = 10, d1 = 8, d2 = 4, center = true);
translate([45, 20, 0]) cylinder(h = 8, r1 = 0, r2 = 5);
