// Type error: cylinder height h is a string ("x") on line 3; a good diagnostic points at h = "x" on line 3 (OpenSCAD 2021.01 silently falls back to h = 1 without any warning).

cylinder(h = "x", r = 1);
