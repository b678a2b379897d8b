// Syntax error: the block comment opened on line 4 is never closed; a good diagnostic points at the '/*' on line 4 (unterminated comment at end of file).

cube(5);
/* this comment never ends
translate([10, 0, 0]) cube(5);
