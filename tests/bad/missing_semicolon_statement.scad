// Syntax slip: missing ';' after cube(10) on line 3, so 'translate(...) cube(5)' on line 4 becomes a child of cube; a good diagnostic points at line 3 saying cube takes no children / ';' is probably missing (OpenSCAD 2021.01 only warns "cube() does not support child modules" and drops the translated cube).

cube(10)
translate([20, 0, 0]) cube(5);
