// 2-D shapes lifted into space: straight, tapered and turned, with holes,
// 2-D booleans and transforms in the plane.
linear_extrude(5) difference() { square(10); translate([5, 5]) circle(3); }
translate([15, 0, 0]) linear_extrude(height = 8, scale = 0.3) square(6, center = true);
translate([30, 0, 0]) linear_extrude(height = 6, scale = 0.5) translate([2, 1]) circle(3);
translate([45, 0, 0]) linear_extrude(height = 4, scale = 1.6, center = true) rotate(30) scale([1, 0.5]) circle(3);
translate([0, 20, 0]) rotate_extrude() translate([5, 0]) circle(1);
translate([20, 20, 0]) rotate_extrude() polygon([[2, 0], [5, 0], [4, 3], [2, 6]]);
translate([35, 20, 0]) rotate_extrude(angle = 270) translate([2, 0]) square([2, 4]);
translate([50, 20, 0]) rotate_extrude(angle = -120) translate([-5, 0]) square([2, 3]);
translate([0, 40, 0]) linear_extrude(height = 3, scale = 0) polygon(points = [[0, 0], [10, 0], [10, 10], [0, 10], [2, 2], [8, 2], [8, 8], [2, 8]], paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
translate([20, 40, 0]) linear_extrude(4) union() { square(6); translate([3, 3]) circle(4); }
translate([35, 40, 0]) linear_extrude(4) intersection() { square(8); translate([8, 4]) circle(5); }
translate([50, 40, 0]) linear_extrude(3) translate([0, 0, 7]) rotate([20, 0, 0]) mirror([1, 0]) polygon([[0, 0], [6, 0], [3, 6]]);
translate([0, 60, 0]) rotate_extrude(angle = 90) translate([3, 0]) circle(2);
translate([20, 60, 0]) rotate_extrude() scale([1, 2]) translate([4, 0]) circle(1);
translate([35, 60, 0]) rotate_extrude() square([3, 2]);
translate([50, 60, 0]) rotate_extrude() intersection() { circle(2); translate([0, -1]) square([4, 3]); }
