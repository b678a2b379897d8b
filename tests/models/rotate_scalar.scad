// Exercises rotate with a single number: a rotation about the z axis (90, 180, 270, -90), also given as a = named argument and from a loop variable.

rotate(90) cube([2, 4, 6]);
translate([20, 0, 0]) rotate(180) cube([2, 4, 6]);
translate([40, 0, 0]) rotate(a = 270) cube([2, 4, 6]);
translate([60, 0, 0]) rotate(-90) cube([2, 4, 6]);
quarter = 90;
for (k = [0 : 3]) translate([0, 40, 0]) rotate(k * quarter) translate([5, 0, 0]) cube([4, 1, 1]);
