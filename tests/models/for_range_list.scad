// Exercises for loops over a range, a stepped range, a list of numbers, a list of vectors, and a list from a variable.

for (i = [0 : 3]) translate([i * 10, 0, 0]) cube(3);
for (i = [0 : 20 : 40]) translate([i, 20, 0]) sphere(r = 2);
for (h = [2, 5, 8]) translate([h * 5, 40, 0]) cylinder(h = h, r = 2);
for (p = [[0, 60, 0], [15, 60, 5], [30, 60, 10]]) translate(p) cube([4, 4, 2]);
sizes = [1, 2, 3];
for (s = sizes) translate([0, 0, 20 + s * 10]) cube(s);
