resize([10, 5, 5]) sphere(2);
