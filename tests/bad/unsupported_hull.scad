// Unsupported construct: hull() on line 3 (valid OpenSCAD, but not a box/cylinder/sphere tree); a good diagnostic names 'hull' at line 3 as unsupported.

hull() {
    cube(5);
    translate([20, 0, 0]) sphere(r = 3);
}
