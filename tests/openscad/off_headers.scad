// OFF files with CGAL's header prefixes (texture coordinates, colours,
// normals, a homogeneous coordinate, a dimension), read as OpenSCAD reads them.
translate([0, 0, 0]) scale([2, 4, 2]) import("off_headers/NOFF.off");
translate([3, 0, 0]) scale([2, 4, 3]) import("off_headers/CNOFF.off");
translate([6, 0, 0]) scale([2, 4, 4]) import("off_headers/STOFF.off");
translate([9, 0, 0]) scale([2, 4, 5]) import("off_headers/4OFF.off");
translate([12, 0, 0]) scale([2, 4, 6]) import("off_headers/nOFF.off");
translate([15, 0, 0]) scale([2, 4, 7]) import("off_headers/STCN4OFF.off");
