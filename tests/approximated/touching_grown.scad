// An outline that touches itself at a corner, grown with sharp corners:
// each corner is joined with the edge that bounds the same wedge of the
// shape. Two thin triangles meeting at their tips (a difference, so that
// the offset takes the outline of the whole).
linear_extrude(height = 2) offset(delta = 1) difference() {
    union() {
        polygon([[0, 0], [-12, -3], [-12, 3]]);
        polygon([[0, 0], [-3, -12], [3, -12]]);
    }
    translate([-12, -12]) square(1);
}
