// The slice of meshes: an octahedron cut off its equator, and a tilted
// ring polyhedron sphere.
linear_extrude(height = 1) projection(cut = true) translate([0, 0, 0.8])
  polyhedron(points = [[3, 0, 0], [-3, 0, 0], [0, 3, 0], [0, -3, 0], [0, 0, 3], [0, 0, -3]],
    faces = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]);
translate([8, 0, 0]) linear_extrude(height = 2) projection(cut = true) rotate([30, 10, 0]) sphere(r = 3, $fn = 7);
