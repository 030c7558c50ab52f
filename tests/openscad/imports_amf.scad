// AMF meshes: OpenSCAD 2021.01's own AMF export of meshes/knot.scad, and
// the same file zipped (AMF's compressed form).
import("meshes/knot.amf");
translate([10, 0, 0]) rotate([0, 30, 0]) import("meshes/knot_zipped.amf");
