offset(r = 1) square(4);
