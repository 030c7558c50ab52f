// Colours: names, vectors, alpha, hex, nesting, and a name OpenSCAD does
// not know (exported as color([-1, -1, -1, 1]): no colour).
color("red") cube(8);
translate([12, 0, 0]) color([0.2, 0.6, 1]) sphere(4);
translate([24, 0, 0]) color("green", 0.5) cylinder(h = 8, r = 4);
translate([36, 0, 0]) color("#ff8800") cube(8);
translate([0, 12, 0]) color("nosuchcolour") cube(8);
translate([12, 12, 0]) color("blue") difference() {
    cube(8);
    color("yellow") translate([4, 4, 4]) sphere(4);
}
