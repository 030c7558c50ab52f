// nested_svg.svg centred: its box is OpenSCAD's, each shape scaled by the
// page that the svg elements before it set (see nested_svg.scad).
linear_extrude(height = 2) import("nested_svg.svg", center = true);
