projection(cut = true) sphere(5);
