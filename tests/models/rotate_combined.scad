// Exercises rotate with a combined vector: the angles apply about x first, then y, then z ([90, 0, 90] maps x -> y, y -> z, z -> x), and a three-angle rotation.

rotate([90, 0, 90]) cube([2, 4, 6]);                          // occupies [0..6] x [0..2] x [0..4]
translate([20, 0, 0]) rotate([90, 90, 0]) cube([2, 4, 6]);
translate([40, 0, 0]) rotate([90, 90, 90]) cylinder(h = 8, r = 2);
translate([60, 0, 0]) rotate([180, 0, 90]) cube([2, 4, 6]);
