surface(file = "heights.dat", center = true);
