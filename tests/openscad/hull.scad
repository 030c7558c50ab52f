// hull(): the convex hull of its children, exact (GJK against the parts'
// own support functions: no mesh). Spheres of different radii, a cube with
// a cylinder, a polyhedron with a sphere, a hull cut from a block (its
// surfaces taken with flipped normals), and a 2-D hull extruded.
$fn = 48;
hull() {
  sphere(r = 4);
  translate([14, 0, 0]) sphere(r = 1.5);
}
translate([0, 14, 0]) hull() {
  cube([6, 6, 2], center = true);
  translate([3, 2, 6]) rotate([20, 0, 30]) cylinder(h = 3, r1 = 2, r2 = 1);
}
translate([16, 14, -2]) hull() {
  polyhedron(points = [[0, 0, 0], [6, 0, 0], [0, 6, 0], [0, 0, 6]],
             faces = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]);
  translate([5, 5, 5]) scale([1, 2, 1]) sphere(r = 1.5);
}
translate([-14, 0, 0]) difference() {
  cube([10, 10, 8], center = true);
  hull() {
    translate([-2, -2, 0]) sphere(r = 3);
    translate([3, 3, 4]) cube(2, center = true);
  }
}
translate([0, -14, -3]) linear_extrude(height = 5) hull() {
  circle(r = 3);
  translate([9, 2]) square(3);
  translate([4, -6]) circle(r = 1);
}
// Balls of one radius: a polytope rounded by a ball (a capsule, a plate
// rounded in its plane), written out as exact primitives.
translate([-14, 16, 0]) hull() {
  sphere(r = 1.5);
  translate([6, 4, 3]) sphere(r = 1.5);
}
translate([-16, -16, 0]) hull() {
  for (x = [0, 8], y = [0, 5]) translate([x, y, 0]) sphere(r = 1);
}
// Parallel cylinders over one height (a slot, a plate with round
// corners): the prism of the hull of their circles.
translate([20, -14, 0]) hull() {
  cylinder(h = 2, r = 2);
  translate([8, 3, 0]) cylinder(h = 2, r = 1);
  translate([2, 7, 0]) cylinder(h = 2, r = 1.5);
}
// A 2-D hull of circles twisted, and turned.
translate([30, 6, 0]) linear_extrude(height = 6, twist = 60) hull() {
  translate([-3, 0]) circle(r = 1);
  translate([3, 0]) circle(r = 2);
}
translate([-30, 0, 0]) rotate_extrude() hull() {
  translate([4, 0]) circle(r = 1);
  translate([6, 3]) square(1);
}
