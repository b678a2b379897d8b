// Exercises mirror([0, 1, 1]): reflection across the plane y + z = 0, which swaps y and z with a sign change; also a non-unit normal [0, 2, 0].

mirror([0, 1, 1]) translate([0, 10, 0]) cube([2, 4, 6]);   // ends up at y in [-6, 0], z in [-14, -10]
translate([20, 0, 0]) mirror([0, 2, 0]) cube([2, 4, 6]);   // same as mirror([0, 1, 0])
