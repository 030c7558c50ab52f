// A drawing whose even-odd loops touch at a corner (two squares, a
// circle's hole: tests/openscad/drawing_touching.dxf) summed with a
// square: flattened, its boundary's loops chained through the corner
// where they touch.
$fn = 64;
linear_extrude(1) minkowski() { import("../openscad/drawing_touching.dxf"); square(1); }
