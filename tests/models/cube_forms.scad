// Exercises cube: scalar size, vector size, center=true and center=false, positional center, the default cube(), and size= named.

cube(5);
translate([10, 0, 0]) cube([4, 6, 8]);
translate([30, 0, 0]) cube(6, center = true);
translate([40, 0, 0]) cube([2, 4, 6], center = true);
translate([50, 0, 0]) cube([3, 3, 3], true);
translate([60, 0, 0]) cube(size = [1, 2, 3], center = false);
translate([70, 0, 0]) cube();
