// offset() of text: round, miter and chamfered joins, grown and shrunk
translate([0, 20]) linear_extrude(2) offset(r = 0.6) text("Ge", size = 10);
translate([0, 0]) color("tomato") linear_extrude(3) offset(delta = 0.5) text("Rx", size = 10);
translate([26, 0]) color("gold") linear_extrude(4) offset(delta = 0.4, chamfer = true) text("S", size = 10);
translate([26, 20]) color("skyblue") linear_extrude(3, center = true) offset(r = -0.4) text("O", size = 12);
translate([40, 5]) color("plum") linear_extrude(1.5) offset(delta = -0.3) text("B", size = 12);
// Shrinking a text whose glyphs' boxes are apart: each glyph by itself.
translate([0, 40]) color("lightgreen") linear_extrude(2) offset(r = -0.35) text("Thin", size = 12);
translate([40, 40]) color("salmon") linear_extrude(2.5) offset(delta = -0.3) text("ab", size = 12);
