// Semantic error: call to an unknown function 'squareroot' on line 3 used as a size (maybe 'sqrt'); a good diagnostic names 'squareroot' and points at line 3.

cube(squareroot(16));
