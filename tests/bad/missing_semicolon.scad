// Syntax error: missing ';' after the assignment 'w = 10' on line 3; a good diagnostic points at line 3 (end of the assignment) or at the unexpected 'cube' on line 4, saying ';' was expected.

w = 10
cube(w);
