// projection(cut = false) of an intersection with an upright cylinder:
// the disc met with the shadow of the rest (a T lying along y, whose
// shadow csgrt casts from its pieces cut in bands across z).
linear_extrude(height = 2)
  projection()
    intersection() {
      cylinder(r = 10, h = 20, center = true, $fn = 48);
      rotate([90, 0, 0])
        linear_extrude(height = 30, center = true)
          polygon([[-2, -5], [2, -5], [2, 3], [8, 3], [8, 5], [-8, 5], [-8, 3], [-2, 3]]);
    }
