// Exercises a recursive module with a depth argument: a stepped tower where each level is smaller and the recursion stops at depth 0.

module tower(size, depth) {
    cube([size, size, 5], center = true);
    if (depth > 0)
        translate([0, 0, 5])
            tower(size * 0.75, depth - 1);
}

tower(40, 3);    // four cubes: 40, 30, 22.5, 16.875
