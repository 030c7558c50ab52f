linear_extrude(1) offset(r = 1) square(2);
translate([5, 0]) linear_extrude(1) offset(delta = 1) polygon([[0,0],[3,0],[3,1],[1,1],[1,3],[0,3]]);
translate([10, 0]) linear_extrude(1) offset(delta = 1, chamfer = true) polygon([[0,0],[3,0],[3,1],[1,1],[1,3],[0,3]]);
translate([15, 0]) linear_extrude(1) offset(r = -0.3) polygon([[0,0],[3,0],[3,1],[1,1],[1,3],[0,3]]);
translate([0, 6]) linear_extrude(1) offset(r = 0.5) polygon([[0,0],[3,0],[3,1],[1,1],[1,3],[0,3]]);
translate([5, 6]) linear_extrude(1) offset(delta = -0.3) polygon([[0,0],[3,0],[3,1],[1,1],[1,3],[0,3]]);
translate([10, 6]) linear_extrude(1) offset(delta = -0.3, chamfer = true) polygon(points=[[0,0],[4,0],[4,4],[0,4],[1,1],[3,1],[2,3]], paths=[[0,1,2,3],[4,5,6]]);
translate([15, 6]) linear_extrude(1) offset(r = 0.4) union() { square(2); translate([1,1]) square(2); circle(0.5); }
translate([0, 12]) linear_extrude(1) scale([2, 1]) offset(delta = 0.5) polygon([[0,0],[2,0],[1,0.3]]);
translate([6, 12]) linear_extrude(1) offset(r = -0.2) intersection() { square(2); rotate(45) square(2); }
// Combinations of straight polygons offset on the loops of their
// boundary: a difference grown (a frame), a union whose parts overlap
// shrunk, an intersection grown with chamfers.
translate([0, 18]) linear_extrude(1) offset(r = 0.5) difference() { square(4); translate([1, 1]) square(2); }
translate([6, 18]) linear_extrude(1) offset(delta = -0.4) union() { square(3); translate([1.5, 1.5]) square(3); }
translate([12, 18]) linear_extrude(1) offset(delta = 0.4, chamfer = true) intersection() { square(3); rotate(30) square(3); }
// A point repeated: an edge of no length bounds nothing (OpenSCAD's
// rounding idiom on a polygon that repeats its last point).
translate([18, 18]) linear_extrude(1) offset(r = -0.5) offset(r = 1) polygon([[0, 0], [4, 0], [4, 1], [1, 1], [0, 3], [0, 3]]);
