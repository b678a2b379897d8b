// Exercises use <lib/shapes.scad>: only its modules and functions are imported (lib_tube still sees lib_wall inside the library); its top-level marker cube is NOT drawn.

use <lib/shapes.scad>

lib_tube(12, 15);
translate([20, 0, 0]) lib_peg(h = lib_double(5));
