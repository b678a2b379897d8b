// A variable made infinite on line 3 (1e308 * 10) and used as a height on line 4; a good diagnostic points at both.

h = 1e308 * 10;
cylinder(h = h, r = 2);
