// Meshes imported from files (meshes/*.scad, exported by OpenSCAD 2021.01
// as ASCII STL and OFF; knot_binary.stl is knot.stl's triangles as
// binary records), placed and cut like any solid.
import("meshes/part.stl");
translate([12, 0, 0]) import("meshes/part.off");
translate([0, 12, 0]) rotate([30, 0, 0]) import("meshes/knot_binary.stl");
translate([12, 12, 0]) difference() {
  import("meshes/knot.stl");
  cube([12, 12, 1], center = true);
}
