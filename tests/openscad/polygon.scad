// What OpenSCAD 2021.01 leaves out and renders the rest around (csgrt
// warns at each): no points, fewer than 3, a point that is not 2 numbers
// (3 included), a path of 2; an index out of range is dropped from its
// path.
linear_extrude(1) {
  polygon(undef);
  polygon([[0, 0], [1, 0]]);
  polygon([[0, 0], [1, 0], [1, 1, 1, 1]]);
  polygon([[0, 0, 1], [1, 0, 1], [0, 1, 1]]);
  polygon([[0, 0], [1, 0], [0, 1]], paths = [[0, 1]]);
  translate([5, 0]) polygon([[0, 0], [3, 0], [0, 3], [3, 3]], paths = [[0, 1, 9, 3, 2]]);
}
// A bare 2-D polygon in a 3-D model: left out, as OpenSCAD renders it.
polygon([[0, 0], [4, 0], [0, 3]]);
