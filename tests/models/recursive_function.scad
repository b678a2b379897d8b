// Exercises recursive user functions: factorial, sum of a list, and a recursive function with a default accumulator parameter.

function fact(n) = n <= 1 ? 1 : n * fact(n - 1);
function sum(v, i = 0) = i >= len(v) ? 0 : v[i] + sum(v, i + 1);
function count_down(n, acc = []) = n == 0 ? acc : count_down(n - 1, concat(acc, [n]));

cube([fact(4), sum([1, 2, 3]), 2]);                 // [24, 6, 2]
for (k = count_down(3)) translate([0, 0, k * 10]) cube(k);   // cubes 3, 2, 1 at z 30, 20, 10
