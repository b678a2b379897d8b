// Syntax error: a stray ')' after cube(5) on line 3; a good diagnostic points at the second ')' on line 3.

cube(5));
