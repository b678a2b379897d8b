// Exercises reassignment in the same scope: the last assignment wins and takes effect at the first assignment's position (b sees a = 20); OpenSCAD 2021.01 prints a WARNING "a was assigned on line 3 but was overwritten" here, by design.

a = 10;
b = a + 1;        // evaluated with the final a = 20, so b = 21
cube([a, b, 5]);  // cube([20, 21, 5])
a = 20;
