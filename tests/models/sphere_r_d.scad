// Exercises sphere: radius by r, by d (half of it), positional radius, and the default sphere() of radius 1.

sphere(r = 5);
translate([20, 0, 0]) sphere(d = 6);      // radius 3
translate([40, 0, 0]) sphere(4);          // positional radius
translate([60, 0, 0]) sphere();           // radius 1
