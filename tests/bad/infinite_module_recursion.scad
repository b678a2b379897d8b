// Recursion error: module 'tower' calls itself unconditionally (no depth check) on line 5, so it never ends; a good diagnostic reports recursion too deep in 'tower', pointing at line 5.

module tower(size) {
    cube(size);
    translate([0, 0, size]) tower(size);
}

tower(5);
