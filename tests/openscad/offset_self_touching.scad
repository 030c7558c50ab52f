// Offsets of polygons whose outline crosses or touches itself (OpenSCAD
// fills a polygon by parity): grown and shrunk, round, sharp and
// chamfered — the region's boundary cut where it meets itself, stroked.
$fn = 48;
steps = [[0, 0], [10, 0], [10, 10], [20, 10], [20, 20], [10, 20], [10, 10], [0, 10]];
bowtie = [[0, 0], [10, 10], [10, 0], [0, 10]];
star = [for (i = [0:4]) [8 * cos(90 + 144 * i), 8 * sin(90 + 144 * i)]];
linear_extrude(1) offset(r = 0.5) polygon(steps);
translate([25, 0, 0]) linear_extrude(1) offset(delta = 0.5) polygon(bowtie);
translate([0, 25, 0]) linear_extrude(1) offset(r = -0.5) polygon(steps);
translate([25, 25, 0]) linear_extrude(1) offset(delta = -0.4, chamfer = true) polygon(bowtie);
translate([50, 8, 0]) linear_extrude(1) offset(r = 1) polygon(star);
translate([50, 33, 0]) linear_extrude(1) offset(delta = -0.5) polygon(star);
// Grown past its own size: both lobes grown (OpenSCAD reads the polygon
// by parity before offsetting it), one loop.
translate([70, 0, 0]) scale(5) linear_extrude(0.2) offset(delta = 1) polygon([[0, 0], [1, 1], [1, 0], [0, 1]]);
