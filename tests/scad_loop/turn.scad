// `$t` in a top-level assignment: OpenSCAD's --animate sets it before the
// program's own assignments, so each frame turns the bar a quarter more.
a = 360 * $t;
rotate([0, 0, a]) cube([20, 4, 4]);
