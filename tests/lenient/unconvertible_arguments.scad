// Arguments OpenSCAD cannot convert: each warns and takes OpenSCAD's fallback.
cube([1, 2]);
translate([10, 0, 0]) cube([1, 2, "a"]);
translate([20, 0, 0]) scale("s") cube(2);
translate([30, 0, 0]) mirror("m") cube(3);
translate([40, 0, 0]) rotate([1, "b", 0]) cube(4);
translate([50, 0, 0]) rotate("c") cube(5);
translate([1, 2, "a"]) cube(6);
translate([60, 0, 0]) cylinder(r = "r", h = 2);
translate([70, 0, 0]) sphere(r = [1]);
translate([80, 0, 0]) multmatrix("k") cube(7);
