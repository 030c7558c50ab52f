// rotate_extrude of an SVG profile of cubic Bézier curves
// (tests/openscad/vase.svg): each turned curve crossed where X(u)^2 equals
// the line's squared distance from the axis at the curve's height, a
// polynomial of degree 6 in u; and a part turn of it.
rotate_extrude() import("vase.svg");
translate([70, 0, 0]) rotate_extrude(angle = 250) import("vase.svg");
