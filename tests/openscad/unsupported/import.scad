import("part.stl");
