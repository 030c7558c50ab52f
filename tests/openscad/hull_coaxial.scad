// Hulls of cylinders and cones on one axis (a lathe of their profile's
// hull), and a hull of two such hulls side by side (its parts the frustums
// of their profiles' edges).
$fn = 64;
hull() {
    cylinder(h = 4.5, r = 7.5);
    cylinder(h = 7, r = 5);
    translate([0, 0, 2]) cylinder(h = 0.7, r1 = 4.7, r2 = 2);
}
translate([22, 0, 0]) hull() {
    hull() { cylinder(h = 1, r = 4); cylinder(h = 5, r = 2); }
    translate([0, 12, 0]) hull() { cylinder(h = 1, r = 4); cylinder(h = 5, r = 2); }
}
translate([0, 22, 5]) rotate([30, 40, 0]) hull() {
    cylinder(h = 6, r1 = 1, r2 = 4, center = true);
    translate([0, 0, -5]) cylinder(h = 2, r = 2);
    translate([0, 0, 3]) scale([1.5, 1.5, 2]) cylinder(h = 1, r = 1);
}
