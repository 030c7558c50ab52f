// OpenSCAD 2021.01's deprecated `file` of an extrusion, as its export
// still writes it (with a `timestamp`): the drawing imported, scaled by a
// linear extrusion's first `scale` number (the bottom twice the drawing,
// the top [2, 3] times that) or a turn's own `scale`.
linear_extrude(file = "example008.dxf", layer = "G", origin = [0, 0], height = 5, scale = [2, 3]);
translate([-60, 0, 0]) linear_extrude(file = "example008.dxf", layer = "E", origin = [10, 10], height = 8);
translate([0, -80, 0]) rotate_extrude(file = "example008.dxf", layer = "G", origin = [-5, 0], scale = 0.5, angle = 270);
