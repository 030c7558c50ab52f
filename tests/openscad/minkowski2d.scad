// 2-D minkowski(), exact: a shape with circles is its offset by their
// radii (a rounded outline, convex or not); convex shapes sum by the hull
// of their corners' sums, a union operand distributing. Extruded straight,
// twisted and turned; and one left flat at the top level, which OpenSCAD's
// render leaves out of a 3-D model (with a warning).
linear_extrude(height = 3) minkowski() {
  square([10, 6]);
  circle(r = 2);
}
translate([18, 0, 0]) linear_extrude(height = 4) minkowski() {
  polygon([[0, 0], [8, 0], [8, 2], [2, 2], [2, 7], [0, 7]]);
  circle(r = 1);
}
translate([0, 16, 0]) linear_extrude(height = 2) minkowski() {
  square(3);
  polygon([[0, 0], [4, 1], [1, 3]]);
  translate([1, 1]) circle(r = 0.5);
}
translate([16, 18, 0]) linear_extrude(height = 3) minkowski() {
  union() {
    square([2, 6], center = true);
    rotate(45) square([5, 1.5], center = true);
  }
  circle(r = 0.75);
}
translate([-14, 0, 0]) linear_extrude(height = 6, twist = 45) minkowski() {
  square(4, center = true);
  circle(r = 1);
}
translate([-18, 20, 0]) rotate_extrude(angle = 270) translate([5, 0]) minkowski() {
  square([2, 3]);
  circle(r = 0.5);
}
translate([30, 5, 0]) rotate([0, 0, 20]) minkowski() {
  square([4, 3]);
  circle(r = 1);
}
// Polygons that are not convex (an L; a square with a hole, twisted) plus
// a convex one: the polygon moved by a corner of the other, and each
// edge's hull with it.
translate([30, 18, 0]) linear_extrude(height = 2) minkowski() {
  polygon([[0, 0], [9, 0], [9, 2], [3, 2], [3, 8], [0, 8]]);
  polygon([[0, 0], [1.5, 0.5], [0.5, 1.2]]);
}
translate([44, 0, 0]) linear_extrude(height = 3, twist = 30) minkowski() {
  polygon([[-3, -3], [3, -3], [3, 3], [-3, 3], [-1, -1], [1, -1], [1, 1], [-1, 1]],
          paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
  rotate(30) square(1, center = true);
}
