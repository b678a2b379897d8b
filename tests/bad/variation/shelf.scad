// A shelf: two sides and three boards (the model the variants beside it vary).
width = 60;
depth = 20;
height = 90;

// the sides
for (x = [0, width - 2])
    translate([x, 0, 0]) cube([2, depth, height]);

// the boards
for (i = [0 : 2])
    translate([2, 0, i * 40]) cube([width - 4, depth, 2]);
