// Type error: cube size is a string ("big") on line 3, not a number or 3-vector; a good diagnostic points at the argument "big" on line 3.

cube("big");
