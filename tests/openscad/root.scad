// The root modifier: only the subtree marked ! is rendered.
cube(10);
translate([15, 0, 0]) !sphere(5);
translate([0, 15, 0]) cylinder(h = 10, r = 4);
