// Exercises vectors, nested vectors, indexing with [i], chained indexing, and .x .y .z member access.

p = [10, 20, 30];
m = [[1, 2, 3], [4, 5, 6]];
size = [p.x / 2, p.y / 4, p.z / 10];    // [5, 5, 3]
translate(p) cube(size);
translate([p[0], m[1][2], m[0].z]) cube(m[1]);   // at [10, 6, 3], size [4, 5, 6]
v = [p, m[0]];
translate(v[1]) sphere(r = v[0][0] / 5);         // at [1, 2, 3], r = 2
