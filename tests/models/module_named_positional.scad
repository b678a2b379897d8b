// Exercises module calls with positional arguments, named arguments, a mix of both, and named arguments in a different order.

module post(w, h, r = 1, top = true) {
    cube([w, w, h]);
    if (top) translate([w / 2, w / 2, h]) sphere(r = r);
}

post(4, 10);                                   // positional only
translate([10, 0, 0]) post(w = 3, h = 12, r = 2);          // named only
translate([20, 0, 0]) post(5, h = 8, top = false);         // mixed, no sphere
translate([30, 0, 0]) post(top = true, r = 3, h = 6, w = 2); // named, shuffled
