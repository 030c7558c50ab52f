// Circles and ellipses off the axis, twisted and scaled unevenly: each an
// exact leaf in csgrt (src/geometry/twist.rs), OpenSCAD's slices in the limit.
linear_extrude(height = 10, twist = 120) translate([4, 0]) circle(2);
translate([14, 0, 0])
  linear_extrude(height = 10, twist = -90, scale = [0.5, 1.5], center = true)
    translate([1, 1]) scale([1, 0.5]) circle(3);
translate([0, 14, 0]) linear_extrude(height = 10, scale = [2, 0.5]) circle(2);
translate([14, 14, 0])
  linear_extrude(height = 8, twist = 200)
    difference() {
      translate([3, 0]) rotate(30) scale([2, 1]) circle(1.5);
      translate([3.5, 0.5]) circle(0.8);
    }
