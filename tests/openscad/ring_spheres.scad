// Spheres with an explicit $fn of 3 to 8: OpenSCAD's ring polyhedra.
for (n = [3 : 8]) translate([3 * (n - 3), 0, 0]) sphere(r = 1.2, $fn = n);
translate([0, 4, 0]) difference() { sphere(r = 2, $fn = 6); sphere(r = 1.5, $fn = 5); translate([0, 0, 1]) cube(3, center = true); }
translate([8, 4, 0]) sphere(r = 2);
