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
// A polyhedron that is not convex (an L), rounded by a ball: the mesh,
// each triangle's slab, each edge's cylinder and each vertex's ball.
module ell() {
  polyhedron(points = [[0, 0, 0], [6, 0, 0], [6, 2, 0], [2, 2, 0], [2, 5, 0], [0, 5, 0],
                       [0, 0, 2], [6, 0, 2], [6, 2, 2], [2, 2, 2], [2, 5, 2], [0, 5, 2]],
             faces = [[0, 1, 2, 3, 4, 5], [11, 10, 9, 8, 7, 6],
                      [0, 6, 7, 1], [1, 7, 8, 2], [2, 8, 9, 3], [3, 9, 10, 4], [4, 10, 11, 5], [5, 11, 6, 0]]);
}
translate([-20, 16, 0]) minkowski() {
  ell();
  sphere(r = 0.8);
}
// The same L plus a box, and plus a cone turned on its side: the mesh
// moved by one point of the convex operand, and each triangle plus that
// operand (a convex set, cast by its support function).
translate([-20, 30, 0]) minkowski() {
  ell();
  cube([1, 0.5, 1.5]);
}
translate([-4, 30, 0]) minkowski() {
  ell();
  rotate([0, 90, 0]) cylinder(h = 1, r1 = 1, r2 = 0.4);
}
// The L plus a union: the sum distributed, (L + B1) u (L + B2).
translate([12, 30, 0]) minkowski() {
  ell();
  union() {
    cube([1, 1, 1]);
    translate([3, 0, 0]) cube([1, 0.5, 0.5]);
  }
}
