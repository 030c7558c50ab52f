// minkowski(): the sum of convex operands, exact (the sum's support is the
// sum of the operands' supports). A box rounded by a sphere, a turned box
// swept by a cylinder, and a sum distributed over a union, ⊕ (A ∪ B) =
// (⊕ A) ∪ (⊕ B), cut from a plate.
$fn = 48;
minkowski() {
  cube([10, 6, 4], center = true);
  sphere(r = 1.5);
}
translate([18, 0, 0]) minkowski() {
  rotate([0, 0, 30]) cube([6, 3, 2], center = true);
  cylinder(h = 2, r = 1);
}
translate([0, 16, 0]) difference() {
  cube([24, 10, 4], center = true);
  minkowski() {
    union() {
      translate([-6, 0, 0]) cube([4, 4, 10], center = true);
      translate([6, 0, 0]) rotate([0, 0, 45]) cube([4, 4, 10], center = true);
    }
    sphere(r = 0.8);
  }
}
// A convex polyhedron rounded by a ball, turned and stretched.
translate([-18, 0, 0]) rotate([20, 30, 0]) scale([1, 1.5, 1]) minkowski() {
  polyhedron(points = [[0, 0, 0], [6, 0, 0], [0, 5, 0], [1, 1, 4]],
             faces = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]);
  sphere(r = 1);
}
