// An SVG drawing with an svg element inside it, read as OpenSCAD
// 2021.01's libsvg reads it (see nested_svg.svg). One import a model:
// libsvg's stack of containers is one for the whole process, never
// emptied, so the group this drawing leaves open would move every shape
// of the next drawing OpenSCAD reads — an OpenSCAD bug csgrt does not
// copy (nested_svg_centered.scad imports it centred).
linear_extrude(height = 4) import("nested_svg.svg");
