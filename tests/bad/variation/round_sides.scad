// A wider shelf whose sides are round (line 8): not the same program with other numbers.
width = 80;
depth = 25;
height = 120;

// the sides
for (x = [0, width - 2])
    translate([x, 0, 0]) cylinder(r = 2, h = height);

// the boards
for (i = [0 : 2])
    translate([2, 0, i * 55]) cube([width - 4, depth, 2]);
