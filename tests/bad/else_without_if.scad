// Syntax error: 'else' on line 4 without a matching 'if' (the previous statement is a plain cube); a good diagnostic points at 'else' on line 4.

cube(5);
else cube(10);
