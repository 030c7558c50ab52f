linear_extrude(height = 10, twist = 90) square([8, 4], center = true);
translate([12, 0]) linear_extrude(height = 10, twist = -200, scale = 0.5) translate([2, 0]) square(3, center = true);
translate([24, 0]) linear_extrude(height = 10, scale = [0.3, 1.5]) polygon([[0,0],[4,0],[4,1],[1,1],[1,4],[0,4]]);
translate([0, 14]) linear_extrude(height = 12, twist = 360, scale = [0, 0]) square([6, 3], center = true);
translate([14, 14]) linear_extrude(height = 10, twist = 120, center = true) difference() { circle(4); square(3, center = true); }
translate([28, 14]) linear_extrude(height = 10, twist = 1500) polygon([[5,0],[4,1.5],[5,1.5]]);
