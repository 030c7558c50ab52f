text("csg");
