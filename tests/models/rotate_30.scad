// Exercises rotations that are not axis-aligned: 30 degrees about z (scalar), 45 about x, 30 about y, and a combined [30, 45, 60].

rotate(30) cube([10, 2, 2]);
translate([30, 0, 0]) rotate([45, 0, 0]) cube([2, 10, 2]);
translate([60, 0, 0]) rotate([0, 30, 0]) cylinder(h = 10, r = 2);
translate([90, 0, 0]) rotate([30, 45, 60]) cube(4, center = true);
