// Unsupported construct: rotate_extrude on line 3 (a torus from a 2-D circle); a good diagnostic names 'rotate_extrude' at line 3 as unsupported.

rotate_extrude() translate([10, 0]) circle(r = 2);
