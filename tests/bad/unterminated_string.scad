// Syntax error: the string starting at line 3 column 6 is never terminated; a good diagnostic points at the opening '"' on line 3.

echo("hello);
cube(5);
