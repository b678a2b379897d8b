// Exercises function literals: assigned to variables, passed as arguments, returned from functions (closure), called immediately.

sq = function (x) x * x;
add = function (a, b = 1) a + b;
function apply(f, v) = f(v);
function adder(n) = function (x) x + n;

add5 = adder(5);
cube([sq(3), add(2), add(2, b = 4)]);           // [9, 3, 6]
translate([0, 20, 0]) cube([apply(sq, 2), add5(1), (function (y) y / 2)(8)]);  // [4, 6, 4]
