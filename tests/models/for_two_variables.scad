// Exercises a for statement with two loop variables (nested iteration in one for), a grid of cubes.

for (x = [0 : 10 : 20], y = [0, 15])
    translate([x, y, 0]) cube([4, 5, x / 10 + 1]);
