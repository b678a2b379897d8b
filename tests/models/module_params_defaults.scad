// Exercises module parameters with defaults: all defaults, some overridden, all given, and defaults computed from a global variable (defaults are evaluated where the module is defined, so they cannot see other parameters).

unit = 4;

module block(w = 10, d = 5, h = unit, lift = unit / 2) {
    translate([0, 0, lift]) cube([w, d, h]);
}

block();                                    // [10, 5, 4] at z = 2
translate([20, 0, 0]) block(6);             // [6, 5, 4] at z = 2
translate([40, 0, 0]) block(8, 2, 3, 0);    // [8, 2, 3] at z = 0
translate([60, 0, 0]) block(h = 1, w = 3);  // [3, 5, 1] at z = 2
