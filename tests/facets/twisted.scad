// Twisted and unevenly scaled linear_extrude for --facets openscad
// against OpenSCAD's own mesh.
linear_extrude(height = 10, twist = 90) square([4, 5]);
translate([12, 0, 0]) linear_extrude(height = 8, twist = -200, center = true, $fn = 12)
  translate([1, 0]) circle(r = 2, $fn = 9);
translate([0, 14, 0]) linear_extrude(height = 6, scale = [0.4, 1.5])
  polygon([[0, 0], [4, 0], [4, 3], [2, 1.5], [0, 3]]);
translate([14, 14, 0]) linear_extrude(height = 9, twist = 120, scale = 0.5, slices = 7)
  polygon(points = [[-3, -3], [3, -3], [3, 3], [-3, 3], [-1, -1], [1, -1], [1, 1], [-1, 1]], paths = [[0, 1, 2, 3], [4, 7, 6, 5]]);
translate([28, 0, 0]) linear_extrude(height = 7, twist = 60, scale = [0.2, 1], $fs = 0.4)
  square([3, 2], center = true);
translate([28, 14, 0]) linear_extrude(height = 5, twist = 45, scale = 1.6, $fa = 5, $fs = 0.3)
  square(2, center = true);
