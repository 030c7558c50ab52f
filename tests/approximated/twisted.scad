// The hull of a twisted bar less a box, cut into convex polytopes slab by
// slab (each slab's hull of the bar's two ends).
hull() difference() {
    linear_extrude(height = 10, twist = 60, slices = 60) square([8, 2], center = true);
    translate([0, 0, 6]) cube(10);
}
