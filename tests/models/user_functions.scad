// Exercises user functions: default parameters, named and positional arguments, functions calling functions, a function defined after its use.

function double(x) = 2 * x;
function box_size(w, d = 5, h = 2) = [w, d, h];
function area(v) = v[0] * v[1];

cube(box_size(10));                              // [10, 5, 2]
translate([0, 20, 0]) cube(box_size(4, h = 6));  // [4, 5, 6]
translate([0, 40, 0]) cube(box_size(d = 3, w = double(3)));  // [6, 3, 2]
translate([area(box_size(2, 3)), 0, 0]) cube(later(1));      // at x = 6, cube(4)

function later(n) = n + 3;
