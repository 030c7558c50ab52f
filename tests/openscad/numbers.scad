// Number forms OpenSCAD prints: large (1e+06), tiny (rotation residues such
// as 2.22045e-16), inf in a special variable, several top-level statements.
translate([1000000, 0, 0]) translate([-1000000, 0, 0]) rotate([90, 0, 0]) cylinder(h = 10, r = 3, $fa = 1/0);
translate([0, 0, 0.000001]) rotate([0, 0, 33.3333]) cube([7, 0.002, 5]);
translate([10, 0, 0]) rotate([-90, 0, 0]) rotate([0, 0, -180]) cube([5, 5, 5]);
translate([-0, -0, 0]) sphere(0.5);
