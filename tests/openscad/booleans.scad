// union, intersection, difference, nesting, render() and for loops.
module plate() {
    difference() {
        cube([40, 30, 4]);
        for (x = [6 : 7 : 34], y = [6, 15, 24])
            translate([x, y, -1]) cylinder(h = 6, r = 2, $fn = 24);
    }
}
plate();
translate([0, 40, 0]) render(convexity = 2) intersection() {
    cube(12, center = true);
    sphere(8);
}
translate([25, 40, 0]) union() {
    cube([10, 10, 2], center = true);
    cylinder(h = 8, r = 3);
}
translate([45, 40, 0]) difference() {
    sphere(8);
    difference() {
        cube(12, center = true);
        sphere(7);
    }
    translate([0, 0, 5]) cube([20, 20, 4], center = true);
}
