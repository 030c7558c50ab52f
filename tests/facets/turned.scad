// rotate_extrude cases for --facets openscad against OpenSCAD's own mesh.
rotate_extrude($fn = 24) translate([6, 0]) circle(r = 2, $fn = 10);
translate([16, 0, 0]) rotate_extrude(angle = 130, $fn = 30)
  difference() { translate([2, -2]) square([4, 5]); translate([4, 0]) circle(1, $fn = 8); }
translate([0, 16, 0]) rotate_extrude(angle = -75, $fa = 6, $fs = 0.5)
  polygon([[1, 0], [5, 0], [4, 3], [2, 4], [1, 2]]);
translate([16, 16, 0]) rotate_extrude($fn = 7)
  polygon([[-1, -2], [-5, -1], [-4, 3], [-1, 1]]);
translate([32, 8, 0]) rotate_extrude(angle = 270, $fn = 16)
  union() { square([3, 2]); translate([1, 1]) square([3, 3]); }
