// Exercises translate: 3-vector, 2-vector (z = 0), negative and fractional offsets, named v=, and chained translates adding up.

translate([10, 20, 30]) cube(2);
translate([5, 5]) cube(3);
translate([-7.5, -2.5, 0.5]) sphere(r = 1);
translate(v = [0, 40, 0]) cylinder(h = 4, r = 2);
translate([1, 0, 0]) translate([0, 2, 0]) translate([0, 0, 3]) cube(1);   // at [1, 2, 3]
