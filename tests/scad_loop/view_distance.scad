// Only the distance set: OpenSCAD's default turn and centre for the rest.
$vpd = 200;
cube(10);
