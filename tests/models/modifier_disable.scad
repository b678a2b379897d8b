// Exercises the * (disable) modifier: the disabled cube and its transform are dropped entirely; the cylinder and the sphere remain.

cylinder(h = 10, r = 3);
*translate([20, 0, 0]) cube(10);
translate([0, 0, 15]) sphere(r = 2);
