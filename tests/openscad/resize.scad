// 3-D: a sphere to an ellipsoid; a union to a given width, the rest auto.
resize([10, 5, 5]) sphere(r = 2);
translate([14, 0, 0]) resize([8, 0, 0], auto = true) union() { cube([2, 3, 1]); translate([1, 1, 0]) cylinder(r = 1, h = 4); }
// A difference whose far sides stay.
translate([0, 12, 0]) resize([6, 6, 3]) difference() { cube(4, center = true); sphere(r = 1.5); }
// A rotated cube: its exact extent is its corners'.
translate([14, 12, 0]) resize([5, 5, 2]) rotate([20, 30, 40]) cube(2, center = true);
// 2-D: text to a width, height auto; a circle to an ellipse. A size below 0:
// one primitive (OpenSCAD's PolySet) keeps that axis; two children (a CGAL
// Nef polyhedron) are mirrored and stretched.
translate([0, -14, 0]) linear_extrude(height = 1) resize([20, 0], auto = [false, true]) text("Resize");
translate([24, -10, 0]) linear_extrude(height = 2) resize([6, 3]) circle(r = 1);
translate([-8, 0, 0]) resize([0, 0, -3], auto = [false, false, false]) cylinder(r1 = 2, r2 = 0.5, h = 2);
translate([-8, -10, 0]) resize([0, 0, -3]) { cylinder(r1 = 2, r2 = 0.5, h = 2); cube([0.5, 0.5, 2.5]); }
// 2-D at the top level of a 3-D model: left out, with a warning.
translate([-8, 10, 0]) resize([4, 2]) square(1);
