// Exercises ranges [a:b] and [a:s:b] as for-loop sources, a fractional step, a descending range, and a range stored in a variable.

r = [0 : 2];
for (i = r) translate([i * 10, 0, 0]) cube(2);            // x = 0, 10, 20
for (j = [0 : 5 : 15]) translate([0, j + 20, 0]) cube(3); // y = 20, 25, 30, 35
for (k = [1 : 0.5 : 2]) translate([0, 0, k * 20]) sphere(r = k); // z = 20, 30, 40
for (n = [3 : -1 : 1]) translate([-10 * n, 0, 0]) cylinder(h = n, r = 1); // x = -30, -20, -10
