// The view set in the program: OpenSCAD's camera looks at $vpt from $vpd
// away, turned by $vpr.
$vpr = [60, 0, 30];
$vpt = [5, -2, 1];
$vpd = 80;
cube(10);
