// Projections offset, turned and summed: their solids cut into convex
// polytopes, each projected or sliced to a convex polygon (the certified
// approximation), then offset, turned or summed exactly.
$fn = 96;
linear_extrude(2) offset(r = 1) projection() difference() {
    sphere(r = 8);
    cylinder(r = 3, h = 20, center = true);
}
translate([0, 22, 0]) rotate_extrude() translate([5, 0]) projection() sphere(r = 3);
translate([22, 0, 0]) linear_extrude(2) minkowski() {
    projection(cut = true) difference() {
        cube(10, center = true);
        cube([5, 5, 20], center = true);
    }
    square(1);
}
