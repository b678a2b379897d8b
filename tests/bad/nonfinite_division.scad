// An operation that makes NaN: 0/0 as a translation on line 4; a good diagnostic points at 0/0 on line 4.

cube(10);
translate([0, 0, 0/0]) cube(1);
