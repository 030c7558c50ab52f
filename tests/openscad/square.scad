square([4, 2]);
