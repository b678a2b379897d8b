// Exercises assignments overriding an included variable: the main file's later plate_w = 50 wins everywhere, also in plate_area_side computed inside the library (no warning in OpenSCAD 2021.01).

include <lib/defaults.scad>

plate_w = 50;
cube([plate_w, plate_d, plate_t]);                       // cube([50, 20, 2])
translate([0, 0, 10]) cube([plate_area_side, 5, 5]);     // cube([70, 5, 5])
