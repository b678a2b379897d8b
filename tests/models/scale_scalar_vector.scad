// Exercises scale: a scalar (uniform), a vector (non-uniform), named v=, scaling a translated child (the offset is scaled too), and scale of a sphere into an ellipsoid.

scale(2) cube(3);                                   // 6 x 6 x 6
translate([20, 0, 0]) scale([1, 2, 3]) cube(4);     // 4 x 8 x 12
translate([40, 0, 0]) scale(v = [0.5, 0.5, 2]) cylinder(h = 5, r = 4);
scale([2, 1, 1]) translate([30, 20, 0]) cube(2);    // at [60, 20, 0], 4 x 2 x 2
translate([0, 40, 0]) scale([3, 1, 0.5]) sphere(r = 4);
