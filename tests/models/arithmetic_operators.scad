// Exercises arithmetic: + - * / % ^ on numbers, unary minus, precedence (^ binds tighter than unary minus), and vector + - * scalar.

a = 7;
b = 2;
sum = a + b;          // 9
diff = a - b;         // 5
prod = a * b;         // 14
quot = a / b;         // 3.5
rem = a % 3;          // 1
pw = b ^ 3;           // 8
neg = -b ^ 2;         // -4
cube([sum, diff, prod]);
translate([-neg, 0, 0]) cube([quot, rem, pw]);          // at x = 4
v = [1, 2, 3] + [4, 5, 6] - [1, 1, 1];                  // [4, 6, 8]
translate(-v) cube(v * 2);                              // at [-4, -6, -8], size [8, 12, 16]
translate([0, 0, 30]) cube([2 * (3 + 1), 10 / 2 * 2, 2 + 3 * 4]); // [8, 10, 14]
