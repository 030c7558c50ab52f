// A 2-D model (its first statement 2-D): its shapes shown as OpenSCAD's
// preview shows them, slabs 1 thick centred on their plane, under their
// 3-D transforms; a solid among them is left out, as OpenSCAD's render
// leaves it out (with a warning).
difference() { square(10); translate([5, 5]) circle(3); }
translate([15, 0, 0]) rotate([60, 0, 0]) circle(4, $fn = 6);
translate([0, 15, 0]) union() { square(4); translate([2, 2]) circle(3); cube(5); }
translate([15, 15, 0]) cube([8, 8, 2], center = true);
