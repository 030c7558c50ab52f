// 2-D hulls of combinations: their boundary's pieces (polygon edges and
// circles cut where they cross, kept where the shape is on one side only)
// give the points and arcs the hull is the hull of; the hull is the
// polygon through its tangent points with each arc's cap joined, exact.
// Turned (Mendel90's washers and fillets: a quarter disc in a hull),
// extruded straight and twisted.
$fn = 64;
module fillet_profile(w, h, r)
  hull() {
    square([1, h]);
    square([w, 1]);
    translate([w - r, h - r]) intersection() {
      circle(r = r);
      square([r, r]);
    }
  }
rotate_extrude() fillet_profile(4, 5, 1.5);
translate([14, 0, 0]) rotate_extrude(angle = 270) translate([2, 0]) fillet_profile(3, 4, 2);
// A lens (two discs met) with a point; a disc less a square (the hull
// keeps the disc's far arc and the cut's corners); a ring (its hole
// adds nothing).
translate([0, 14, 0]) linear_extrude(height = 3) hull() {
  intersection() {
    circle(r = 4);
    translate([4, 0]) circle(r = 4);
  }
  translate([2, 7]) square(0.5);
}
translate([14, 14, 0]) linear_extrude(height = 3) hull() {
  difference() {
    circle(r = 4);
    translate([-1, -5]) square(10);
  }
  translate([3, 3]) circle(r = 1);
}
translate([-14, 14, 0]) linear_extrude(height = 2, twist = 90) hull() {
  difference() {
    circle(r = 4);
    circle(r = 3);
  }
  translate([5, 0]) intersection() {
    circle(r = 2);
    translate([0, -2]) square(4);
  }
}
// Shapes that only touch: the difference of a square and its own left
// half keeps the right half's corners only.
translate([-14, 0, 0]) linear_extrude(height = 2) hull() {
  difference() {
    square(6);
    square([3, 6]);
  }
  translate([1, 7]) circle(r = 0.5);
}
