// Exercises include <lib/shapes.scad>: its modules, function and variable become available AND its top-level marker cube at [-30, -30, 0] is drawn.

include <lib/shapes.scad>

lib_tube(13, 15);
translate([20, 0, 0]) lib_peg(h = lib_double(5));
translate([40, 0, 0]) cube([lib_wall, lib_wall, lib_double(lib_wall)]);
