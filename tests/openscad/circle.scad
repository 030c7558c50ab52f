circle(r = 3);
