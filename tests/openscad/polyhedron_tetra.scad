polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);
// OpenSCAD drops an index out of range from its face, and a face left
// with fewer than 3 points: the same tetrahedron, beside the first.
translate([2, 0, 0]) polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], faces = [[0, 1, 2], [0, 3, 1, 9], [0, 2, 3], [1, 3, 2], [0, 1, 7]]);
