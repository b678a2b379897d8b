// Include error: the file lib/does_not_exist.scad included on line 3 does not exist; a good diagnostic names the path and points at line 3.

include <lib/does_not_exist.scad>

cube(5);
