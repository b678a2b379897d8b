// Exercises math built-ins sqrt pow abs min max floor ceil round, with their results used as sizes and positions.

a = sqrt(16);              // 4
b = pow(2, 3);             // 8
c = abs(-5);               // 5
d = min(7, 3, 9);          // 3
e = max([2, 11, 6]);       // 11 (vector form)
f = floor(2.7);            // 2
g = ceil(2.1);             // 3
h = round(2.5);            // 3
i = round(-1.4);           // -1
cube([a, b, c]);
translate([d, e, 0]) cube([f, g, h]);
translate([i, 0, 20]) sphere(r = min(a, b) / 2);    // at x = -1, r = 2
