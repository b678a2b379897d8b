// A rack whose library include is missing: OpenSCAD warns and goes on; nothing from it is used.
include <../library/modules.scad>
use <../library/helpers.scad>
for (i = [0 : 3]) translate([0, i * 20, 0]) cube([100, 2, 30]);
cube([2, 62, 30]);
