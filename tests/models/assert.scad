// Exercises assert as a statement (with and without a message) and as an expression (assert(cond) expr) that passes.

w = 12;
assert(w > 0);
assert(w < 100, "width must be under 100");
d = assert(w % 2 == 0, "width must be even") w / 2;   // 6
cube([w, d, 3]);
assert(d == 6) translate([0, 0, 5]) sphere(r = 2);
