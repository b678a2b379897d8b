// Syntax error: '1.2.3' is not a number (two decimal points) on line 3; a good diagnostic points at '.3' / the literal 1.2.3 on line 3.

cube(1.2.3);
