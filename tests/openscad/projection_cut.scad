linear_extrude(height=2) projection(cut=true) translate([0,0,3]) difference() { sphere(r=5); cube([4,4,20], center=true); }
translate([12,0,0]) linear_extrude(height=3, center=true) projection(cut=true) rotate([30,20,0]) cube([6,4,8], center=true);
translate([0,12,0]) linear_extrude(height=1) difference() { square(10, center=true); projection(cut=true) rotate([90,0,0]) cylinder(r=3, h=20, center=true); }
