// Syntax error: the '(' of translate on line 3 is never closed (missing ')' before ' cube'); a good diagnostic points at 'cube' on line 3 or the '(' after translate, expecting ')'.

translate([10, 0, 0] cube(5);
