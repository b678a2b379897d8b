// Exercises comparisons (< <= > >= == !=), logical && || !, ternary (nested), used to pick sizes and positions.

a = 5;
b = 8;
lt = a < b ? 1 : 0;       // 1
le = a <= 5 ? 2 : 0;      // 2
gt = b > a ? 3 : 0;       // 3
ge = b >= 9 ? 0 : 4;      // 4
eq = a == 5 ? 5 : 0;      // 5
ne = a != b ? 6 : 0;      // 6
both = (a > 1 && b > 1) ? 10 : 1;          // 10
either = (a > 100 || b == 8) ? 12 : 1;     // 12
negation = !(a > b) ? 14 : 1;              // 14
tier = a < 3 ? 1 : a < 7 ? 2 : 3;          // nested ternary: 2
cube([lt + le + gt, ge + eq + ne, tier]);  // [6, 15, 2]
translate([20, 0, 0]) cube([both, either, negation]);
