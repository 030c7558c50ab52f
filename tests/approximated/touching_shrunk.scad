// An outline that touches itself at a corner, shrunk with sharp corners:
// a square with two thin triangular holes meeting at their tips.
linear_extrude(height = 2) offset(delta = -1) difference() {
    square(28);
    polygon([[14, 14], [2, 11], [2, 17]]);
    polygon([[14, 14], [11, 2], [17, 2]]);
}
