// A cube that stands still and a ball that moves away from it.
cube(10);
translate([40 * $t, -8, 0]) sphere(3);
