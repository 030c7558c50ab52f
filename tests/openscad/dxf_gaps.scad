// DXF lines whose ends meet within OpenSCAD's grid of 2^-10 (up to 4e-4
// apart), in shuffled order and directions: joined into closed paths as
// OpenSCAD's DxfData joins them, filled even-odd (the half-disc a hole).
linear_extrude(height = 2) import("dxf_gaps.dxf");
translate([0, 14, 0]) linear_extrude(height = 1) import("dxf_gaps.dxf", $fn = 7);
