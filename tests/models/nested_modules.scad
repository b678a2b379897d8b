// Exercises modules defined inside modules: the inner module sees the outer module's parameters and is local to it.

module frame(w, h, bar = 2) {
    module rail(len) {
        cube([len, bar, bar]);
    }
    module stile(len) {
        cube([bar, bar, len]);
    }
    rail(w);
    translate([0, 0, h - bar]) rail(w);
    stile(h);
    translate([w - bar, 0, 0]) stile(h);
}

frame(30, 20);
translate([0, 10, 0]) frame(w = 40, h = 10, bar = 3);
