// import() of an SVG drawing (tests/openscad/drawing.svg): rounded and
// plain rectangles, a circle, a turned ellipse, a polygon, cubic,
// quadratic and smooth curves, a hole by even-odd, an elliptical arc,
// strokes with miter, round, square and bevel joins and butt, round and
// square caps, two open subpaths crossing (even-odd within one element),
// group transforms, a viewBox onto a page in mm; once as the
// file places it, once centred at another dpi.
linear_extrude(height = 5) import("drawing.svg");
translate([0, -70, 0]) linear_extrude(height = 3) import("drawing.svg", center = true, dpi = 96);
