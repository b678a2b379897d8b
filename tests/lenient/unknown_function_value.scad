// An unknown function gives undef: the cube it sizes falls back to OpenSCAD's default size.
cube(10);
translate([20, 0, 0]) cube(squareroot(16));
