// Unsupported construct: surface() on line 3 (a height map from a data file); a good diagnostic names 'surface' at line 3 as unsupported.

surface(file = "heightmap.dat", center = true);
