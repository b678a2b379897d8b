// Unsupported construct: square on line 3 is a 2-D primitive (only 3-D cube/cylinder/sphere are supported); a good diagnostic names 'square' at line 3 as unsupported/2-D.

square([10, 20]);
