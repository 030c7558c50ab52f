// Offsets of combinations with circles, on the strokes of their boundary
// (straight stretches and arcs): OpenSCAD's rounding idiom (shrink after
// growing: fillets in the inner corners), the opening idiom (grow after
// shrinking), a difference grown round and with miters, a union shrunk
// with chamfers, and a rounded plate turned.
$fn = 64;
linear_extrude(2) offset(r = -2) offset(r = 2) { square([10, 4]); translate([8, 0]) circle(4); square([3, 12]); }
translate([20, 0]) linear_extrude(2) offset(r = 1) difference() { circle(6); square(5); }
translate([0, 20]) linear_extrude(2) offset(delta = 1) difference() { circle(6); square(5); }
translate([20, 20]) linear_extrude(2) offset(delta = -1, chamfer = true) union() { circle(6); square(8); }
translate([-16, 0]) linear_extrude(2) offset(r = 1) offset(r = -1) union() { circle(4); translate([5, 0]) circle(3); translate([0, -0.8]) square([9, 1.6]); }
translate([-16, 20]) rotate_extrude() offset(r = -0.5) union() { translate([3, 0]) square([3, 4]); translate([6, 2]) circle(2); }
