// A drawing whose even-odd loops touch at a corner (two squares) with a
// circle's hole, grown through the strokes of its boundary: the hole
// shrinks to radius 1 (drawing_touching_sum.scad sums it with a square).
$fn = 64;
linear_extrude(1) offset(r = 2.5) import("drawing_touching.dxf");
