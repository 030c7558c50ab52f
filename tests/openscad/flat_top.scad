// 2-D shapes where solids are expected: OpenSCAD's preview slabs.
difference() { square(10); translate([5, 5]) circle(3); }
translate([15, 0, 0]) rotate([60, 0, 0]) circle(4, $fn = 6);
translate([0, 15, 0]) union() { cube([4, 4, 4]); translate([2, 2]) circle(3); }
translate([15, 15, 0]) difference() { cube([8, 8, 2], center = true); square(3, center = true); }
