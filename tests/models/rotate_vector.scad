// Exercises rotate with a vector of angles about single axes: [90,0,0] (about x), [0,90,0] (about y), [0,0,90] (about z), [0,0,180], negative angles.

rotate([90, 0, 0]) cube([2, 4, 6]);                           // y -> z, z -> -y
translate([20, 0, 0]) rotate([0, 90, 0]) cube([2, 4, 6]);     // z -> x, x -> -z
translate([40, 0, 0]) rotate([0, 0, 90]) cube([2, 4, 6]);     // x -> y, y -> -x
translate([60, 0, 0]) rotate([0, 0, 180]) cube([2, 4, 6]);
translate([80, 0, 0]) rotate([-90, 0, 0]) cylinder(h = 10, r = 2);   // cylinder along +y
translate([100, 0, 0]) rotate([0, -90, 0]) cylinder(h = 10, r = 2);  // cylinder along -x
