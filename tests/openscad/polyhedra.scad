// Polyhedra csgrt reads as meshes: non-convex faces, a hole through,
// CSG with solids, a mirror.
module star_prism(n = 5, r1 = 4, r2 = 1.8, h = 3) {
  pts = [for (z = [0, h]) for (i = [0 : 2 * n - 1])
           let (r = i % 2 == 0 ? r1 : r2, a = 180 * i / n) [r * cos(a), r * sin(a), z]];
  m = 2 * n;
  polyhedron(points = pts,
    faces = concat(
      [[for (i = [m - 1 : -1 : 0]) i]],            // bottom, clockwise from below
      [[for (i = [0 : m - 1]) m + i]],             // top
      [for (i = [0 : m - 1]) [i, (i + 1) % m, m + (i + 1) % m, m + i]]));
}
module frame(a = 5, b = 3, h = 1.5) {
  // A square ring: outer corners 0-3, inner 4-7, then the same at z = h.
  o = [[-a, -a], [a, -a], [a, a], [-a, a]];
  i = [[-b, -b], [b, -b], [b, b], [-b, b]];
  pts = [for (z = [0, h]) each [for (p = concat(o, i)) [p[0], p[1], z]]];
  faces = concat(
    [for (k = [0 : 3]) [k, 4 + k, 4 + (k + 1) % 4, (k + 1) % 4]],            // bottom
    [for (k = [0 : 3]) [8 + k, 8 + (k + 1) % 4, 12 + (k + 1) % 4, 12 + k]],   // top
    [for (k = [0 : 3]) [k, (k + 1) % 4, 8 + (k + 1) % 4, 8 + k]],            // outer sides
    [for (k = [0 : 3]) [4 + k, 12 + k, 12 + (k + 1) % 4, 4 + (k + 1) % 4]]); // inner sides
  polyhedron(points = pts, faces = faces);
}
module octahedron(r = 1) {
  polyhedron(points = [[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0], [0, 0, r], [0, 0, -r]],
    faces = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]);
}
star_prism();
translate([12, 0, 0]) frame();
translate([0, 12, 0]) difference() {
  cube(6, center = true);
  scale([1, 1, 1.2]) octahedron(3.8);
}
translate([12, 12, 0]) mirror([1, 0, 0]) rotate([0, 0, 20]) star_prism(n = 3, r1 = 3, r2 = 1.2, h = 2);
translate([-9, 6, 0]) intersection() {
  sphere(r = 3);
  octahedron(3.6);
}
