// A name plate: a rounded, chamfered plate with two mounting holes and
// engraved, raised and tapered lettering (linear_extrude, offset, text).
difference() {
    union() {
        linear_extrude(height = 4)
            offset(r = 3) square([74, 26]);
        translate([0, 0, 4]) linear_extrude(height = 1.5, scale = 0.96)
            offset(delta = 1.5, chamfer = true) translate([1.5, 1.5]) square([71, 23]);
    }
    for (x = [3, 71]) translate([x, 13, -1]) cylinder(h = 8, r = 2.2);
    translate([37, 13, 4.5]) linear_extrude(height = 2)
        text("csgrt", size = 11, font = "Liberation Sans:style=Bold", halign = "center", valign = "center");
}
translate([37, -9, 0]) linear_extrude(height = 2, scale = 0.9)
    text("exact CSG", size = 6, halign = "center", valign = "center");
