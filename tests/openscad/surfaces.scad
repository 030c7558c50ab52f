// surface() from a .dat grid (a comment, a blank line, a tab) and from a
// PNG image, plain and inverted, cut and moved like any solid.
surface(file = "heights.dat", center = true);
translate([10, 0, 0]) scale([1, 1, 0.05]) surface(file = "relief.png");
translate([0, 10, 0]) difference() {
  scale([1, 1, 0.05]) surface(file = "relief.png", invert = true);
  translate([4, 3, -10]) cylinder(r = 2, h = 20);
}
