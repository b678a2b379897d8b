// Exercises a cylinder given both d and r: d wins (radius 4, not 1); OpenSCAD 2021.01 prints a WARNING "Ignoring radius variable 'r' as diameter 'd' is defined too", by design.

cylinder(h = 10, r = 1, d = 8);
