// Hulls of an intersection and of a difference: csgrt cuts them into
// convex polytopes within 1/8192 of their size (the certified
// approximation) and takes the hull of those.
$fn = 48;
hull() {
    intersection() { sphere(r = 10); cube([16, 16, 16], center = true); }
    translate([14, 0, -8]) cylinder(r = 2, h = 4);
}
translate([0, -25, -5]) hull() difference() {
    cube(10);
    translate([10, 10, 10]) sphere(r = 6);
}
