// Semantic error: unknown variable 'widht' (typo for 'width') used as a cube size on line 4; a good diagnostic names 'widht' at line 4 (OpenSCAD only warns and draws nothing useful).

width = 10;
cube([widht, 5, 5]);
