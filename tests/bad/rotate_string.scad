// Type error: rotate angle is a string ("a") on line 3, not a number or vector; a good diagnostic points at the argument "a" on line 3.

rotate("a") cube(10);
