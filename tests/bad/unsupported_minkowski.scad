// Unsupported construct: minkowski() on line 3 (valid OpenSCAD, not supported); a good diagnostic names 'minkowski' at line 3 as unsupported.

minkowski() {
    cube([20, 10, 2]);
    sphere(r = 1);
}
