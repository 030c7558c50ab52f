// Circles, cylinders and spheres by OpenSCAD's fragment rule: $fa/$fs by
// default, an explicit $fn, cones and a centred prism. solids.off is
// OpenSCAD 2021.01's own mesh of it (openscad -o solids.off solids.scad).
sphere(r = 5);
translate([12, 0, 0]) sphere(r = 3, $fn = 10);
translate([0, 12, 0]) cylinder(h = 6, r1 = 3, r2 = 1, $fa = 6, $fs = 0.5);
translate([12, 12, 0]) linear_extrude(height = 2) circle(r = 4, $fn = 12);
translate([24, 0, 0]) cylinder(h = 4, r = 2, center = true, $fn = 9);
translate([24, 12, 0]) sphere(r = 0.8, $fs = 0.1);
