// text(): layout (halign, valign, spacing, size, font styles, kerning),
// glyphs extruded straight and tapered, engraved, turned and mirrored,
// and a bare 2-D text at the top level (last: OpenSCAD's render leaves a
// 2-D child of a 3-D model out, with a warning).
translate([0, 14, 0]) linear_extrude(height = 2)
    text("AVWa fi", size = 7, font = "Liberation Sans:style=Bold", halign = "center", spacing = 1.1);
translate([0, 26, 0]) linear_extrude(height = 3, scale = 0.7)
    text("Tg@", size = 8, valign = "center", halign = "right", font = "Liberation Sans:style=Italic");
difference() {
    translate([22, -4, -2]) cube([24, 12, 3]);
    translate([34, 2, 0]) linear_extrude(height = 2)
        text("OK", size = 8, halign = "center", valign = "center", font = "Liberation Sans:style=Bold Italic");
}
translate([-30, 0, 0]) rotate([0, 0, 20]) mirror([1, 0, 0]) scale([1, 1.5])
    linear_extrude(height = 1.5, center = true) text("Qe", size = 6, valign = "top");
text("csg");
