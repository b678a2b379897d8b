// Exercises cylinder in every spelling: h r; h r1 r2; positional (h, r1, r2) and (h, r1) (r2 stays 1); d; d1 d2; center=true; cone with r2=0; inverted cone with r1=0; a mix of r1 with d2.

cylinder(h = 10, r = 3);                         // plain
translate([10, 0, 0]) cylinder(h = 10, r1 = 3, r2 = 1);    // frustum
translate([20, 0, 0]) cylinder(10, 3, 1);        // positional h, r1, r2
translate([30, 0, 0]) cylinder(10, 3);           // positional h, r1: r2 keeps its default 1, so this is a cone from radius 3 to 1 (OpenSCAD 2021.01)
translate([40, 0, 0]) cylinder(h = 10, d = 6);   // diameter
translate([50, 0, 0]) cylinder(h = 10, d1 = 6, d2 = 2);    // diameters
translate([60, 0, 0]) cylinder(h = 10, r = 3, center = true);  // centered on z = 0
translate([70, 0, 0]) cylinder(h = 10, r1 = 3, r2 = 0);    // cone to a point
translate([80, 0, 0]) cylinder(h = 10, r1 = 0, r2 = 3);    // inverted cone
translate([90, 0, 0]) cylinder(h = 10, r1 = 3, d2 = 2);    // r1 with d2
translate([100, 0, 0]) cylinder(r = 2, h = 4);   // named, reversed order
