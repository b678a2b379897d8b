// Exercises lexical scoping: module parameters and module-body variables shadow globals, for-loop variables are local, and an assignment inside a braced block under a transform stays local to that block.

size = 10;

module box(size = 3) {
    cube(size);              // the parameter, 3
}

module boxed() {
    size = 5;                // shadows the global inside this module only
    translate([20, 0, 0]) cube(size);
}

box();
boxed();
for (size = [1, 2]) translate([40 + size * 10, 0, 0]) cube(size);   // loop variable shadows
translate([0, 30, 0]) {
    size = 7;                // local to this block
    cube(size);
}
translate([0, 60, 0]) cube(size);   // the global, 10
