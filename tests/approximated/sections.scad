// Cut projections inside what is cut into convex polytopes: the section's
// solid cut into pieces, each sliced exactly by the plane and swept.
$fn = 40;
// The shadow of a difference with a section in it.
linear_extrude(height = 1) projection() difference() {
    linear_extrude(height = 1) projection(cut = true) sphere(r = 5);
    cube(4);
}
// A hull of an intersection with a section of a raised ball in it.
translate([14, 0, 0]) hull() {
    intersection() {
        linear_extrude(height = 3) projection(cut = true) translate([0, 0, 1]) sphere(r = 5);
        cube(8);
    }
    translate([0, 0, 6]) sphere(r = 1);
}
// A sum of a difference with a section of a drilled ball in it.
translate([0, 14, 0]) minkowski() {
    difference() {
        linear_extrude(height = 2) projection(cut = true)
            difference() { sphere(r = 5); cylinder(r = 2, h = 20, center = true); }
        cube(3);
    }
    sphere(r = 0.5);
}
