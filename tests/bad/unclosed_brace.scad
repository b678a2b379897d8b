// Syntax error: the '{' opened by union() on line 3 is never closed; a good diagnostic reports unexpected end of file and points back at the '{' on line 3.

union() {
    cube(10);
    translate([20, 0, 0]) cube(5);
