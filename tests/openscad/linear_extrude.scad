linear_extrude(height = 5) square(3);
