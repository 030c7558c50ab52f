// Modifiers: # highlight (rendered), % background and * disable (left out).
cube(10);
#translate([15, 0, 0]) sphere(5);
%translate([0, 15, 0]) cube(10);
*translate([15, 15, 0]) cube(10);
translate([30, 0, 0]) difference() {
    cube(10);
    #translate([5, 5, 5]) sphere(4);
}
