// Exercises list comprehensions: [for ...], with if, with if/else, with let, with each, nested for, and a for with two variables.

xs = [for (i = [0 : 3]) i * 10];                    // [0, 10, 20, 30]
evens = [for (i = [0 : 6]) if (i % 2 == 0) i];      // [0, 2, 4, 6]
signs = [for (i = [0 : 2]) if (i == 1) 5 else 2];   // [2, 5, 2]
squares = [for (i = [1 : 3]) let (s = i * i) s];    // [1, 4, 9]
flat = [for (p = [[1, 2], [3]]) each p];            // [1, 2, 3]
flat2 = [each [4, 5], 6];                           // [4, 5, 6]
pairs = [for (a = [1, 2]) for (b = [10, 20]) a + b]; // [11, 21, 12, 22]
grid = [for (a = [0, 1], b = [0, 1]) [a, b]];        // 4 points

for (x = xs) translate([x, 0, 0]) cube(2);
translate([0, 20, 0]) cube([len(evens), signs[1], squares[2]]);  // [4, 5, 9]
translate([0, 40, 0]) cube(flat);                                // [1, 2, 3]
translate([20, 40, 0]) cube(flat2);                              // [4, 5, 6]
translate([0, 60, 0]) cube([pairs[0], pairs[3], 2]);             // [11, 22, 2]
for (g = grid) translate([g[0] * 5, g[1] * 5, 30]) sphere(r = 1);
