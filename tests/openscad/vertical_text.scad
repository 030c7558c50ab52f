// Vertical text (direction "ttb" and "btt"), raised from a plate
color("silver") translate([-4, -52, -2]) cube([40, 56, 2]);
color("teal") linear_extrude(3) text("CSG", size = 10, direction = "ttb");
color("orange") translate([18, 0, 0]) linear_extrude(2) text("ray", size = 8, direction = "btt", halign = "center");
color("plum") translate([28, -50, 0]) linear_extrude(1.5) offset(r = 0.4) text("ok", size = 6, direction = "ttb", valign = "bottom");
