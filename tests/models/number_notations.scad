// Exercises number literals in every notation: integer, decimal, leading dot, exponent, negative exponent, capital E, trailing dot.

a = 1;
b = 1.5;
c = .5;
d = 1e1;
e = 2.5e-1;
f = 1E2;
g = 3.;
h = 0.125e+2;
cube([a, b, c]);                          // [1, 1.5, 0.5]
translate([d, 0, 0]) cube([e, f / 10, g]); // at x = 10: [0.25, 10, 3]
translate([0, h, 0]) sphere(r = 2.5e0);    // at y = 12.5
