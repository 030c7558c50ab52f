// Vertical text as OpenSCAD 2021.01 lays it out (Liberation Sans, the
// default; export with fonts-liberation installed): tests/vertical_text.rs
// compares csgrt's layout of each line with `openscad -o vertical.dxf`.
translate([0, 0]) text("AgW", size = 10, direction = "ttb");
translate([60, 0]) text("AgW", size = 10, direction = "btt");
translate([120, 0]) text("AgW", size = 10, direction = "ttb", halign = "center", valign = "center");
translate([180, 0]) text("Hi! 7", size = 8, direction = "ttb", halign = "right", valign = "top", spacing = 1.3);
translate([240, 0]) text("fjord", size = 12, direction = "ttb", valign = "bottom", font = "Liberation Sans:style=Bold");
// The same comparison of horizontal text, as a control: a long line.
translate([0, -150]) text("The quick brown fox jumps over", size = 10);
