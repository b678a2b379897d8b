// Type error: translate takes a 2- or 3-vector, given the scalar 5 on line 3; a good diagnostic points at the argument 5 on line 3.

translate(5) cube(10);
