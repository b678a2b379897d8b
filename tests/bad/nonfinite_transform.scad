// Finite translations that add up past the largest double on line 3; a good diagnostic points at the cube on line 3.

translate([1e308, 0, 0]) translate([1e308, 0, 0]) cube(1);
