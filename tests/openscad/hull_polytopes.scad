// Hulls and sums of polytopes only (boxes, polyhedra, straight
// extrusions of polygons): csgrt writes each out as one convex polyhedron.
hull() {
  cube([6, 6, 2], center = true);
  translate([2, 1, 6]) rotate([20, 30, 10]) cube([2, 3, 1]);
  translate([-3, 0, 3]) polyhedron([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, 2]], [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]);
}
translate([14, 0, 0])
  minkowski() {
    cube([6, 4, 2], center = true);
    translate([1, 1, 0]) cube([2, 1, 1.5]);
  }
translate([0, 14, 0])
  hull() {
    linear_extrude(height = 4, scale = 0.5) polygon([[0, 0], [6, 0], [6, 2], [2, 2], [2, 6], [0, 6]]);
    translate([5, 5, 5]) cube(1);
  }
translate([14, 14, 0])
  minkowski() {
    hull() { cube(2); translate([4, 0, 0]) cube(1); }
    linear_extrude(height = 1) polygon([[0, 0], [3, 0], [0, 3]]);
    cube([1, 1, 3]);
  }
