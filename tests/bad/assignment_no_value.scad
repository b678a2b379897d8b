// Syntax error: assignment with no value ('a = ;') on line 3; a good diagnostic points at the ';' on line 3, expecting an expression.

a = ;
cube(5);
