// A hull and a Minkowski sum nested in differences that are hulled:
// csgrt cuts the inner ones into their parts' polytopes, hulled and summed.
$fn = 40;
hull() difference() {
    hull() { cube(4); translate([10, 0, 0]) cylinder(r = 2, h = 4); }
    translate([-3, -3, 2.5]) rotate([0, 10, 0]) cube([20, 10, 5]);
}
translate([0, 12, 0]) hull() {
    intersection() {
        minkowski() { cube([6, 3, 2]); sphere(r = 1); }
        translate([3, 0, 0]) cube([8, 8, 8], center = true);
    }
    translate([0, 8, 0]) sphere(r = 0.5);
}
