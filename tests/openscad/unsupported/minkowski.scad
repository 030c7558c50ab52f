minkowski() { cube(4); sphere(1); }
