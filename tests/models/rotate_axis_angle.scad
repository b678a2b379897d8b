// Exercises rotate in axis-angle form rotate(a=..., v=...): about x, about y, about z, about a diagonal axis, and positional rotate(90, [0, 1, 0]).

rotate(a = 90, v = [1, 0, 0]) cube([2, 4, 6]);
translate([20, 0, 0]) rotate(a = 90, v = [0, 1, 0]) cube([2, 4, 6]);
translate([40, 0, 0]) rotate(a = 90, v = [0, 0, 1]) cube([2, 4, 6]);
translate([60, 0, 0]) rotate(a = 120, v = [1, 1, 1]) cube([2, 4, 6]);   // cyclic x -> y -> z
translate([80, 0, 0]) rotate(90, [0, 1, 0]) cylinder(h = 10, r = 2);     // along +x
