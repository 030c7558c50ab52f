// projection(cut = false) extruded: the shadow of a union of a polyhedron,
// a turned cube and a stretched sphere, exact (the union of the faces'
// shadows; an ellipsoid's shadow is an ellipse); cut from a plate, and
// mirrored.
module solids() {
  polyhedron(points = [[0, 0, 0], [8, 0, 1], [2, 7, -2], [3, 2, 9]],
             faces = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]);
  translate([12, 2, 0]) rotate([30, 40, 10]) cube([5, 4, 3], center = true);
  translate([4, -6, 3]) rotate([0, 30, 20]) scale([5, 2, 3]) sphere(1);
}
linear_extrude(height = 2) projection() solids();
translate([0, 0, -6]) linear_extrude(height = 1) difference() {
  translate([-4, -10]) square([22, 20]);
  projection(cut = false) solids();
}
translate([0, 30, 0]) mirror([1, 0, 0]) linear_extrude(height = 3, center = true) projection() rotate([90, 0, 0]) solids();
