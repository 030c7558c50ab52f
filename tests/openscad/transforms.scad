// Transforms: translate, rotate (vector and axis forms), scale, mirror,
// multmatrix, nesting, and a part far from the origin.
translate([0, 0, 0]) rotate([30, 45, 60]) cube(6, center = true);
translate([15, 0, 0]) rotate(a = 37, v = [1, 1, 0]) cylinder(h = 8, r = 2, center = true);
translate([30, 0, 0]) scale([2, 1, 0.5]) sphere(4);
translate([45, 0, 0]) scale(0.5) cube(10, center = true);
translate([60, 0, 0]) mirror([1, 1, 0]) cube([8, 3, 2]);
multmatrix([[1, 0.4, 0, 0], [0, 1, 0, 15], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(6);
translate([15, 15, 0]) rotate([90, 0, 0]) rotate([0, 0, 180]) cylinder(h = 5, r1 = 3, r2 = 1);
translate([30, 15, 0]) rotate(-90) cube([6, 2, 2]);
translate([1e6, 0, 0]) translate([-1e6, 30, 0]) cube(5);
