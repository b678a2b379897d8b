// An unknown module draws nothing: OpenSCAD warns and goes on with the rest.
cube([10, 10, 2]);
translate([0, 0, 2]) cuboid([1, 2, 3]);
