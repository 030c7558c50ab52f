// Strokes of an SVG drawing (tests/openscad/strokes.svg): sharp turns past
// Clipper's miter limit squared, bevels, round joins and caps, butt and
// square caps; and a closed path of cubic, quadratic and smooth curves.
// Nothing here combines by parity, so POV-Ray gets it all.
linear_extrude(height = 4) import("strokes.svg");
