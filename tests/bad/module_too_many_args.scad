// Argument error: user module 'peg' takes 2 parameters but is called with 3 positional arguments on line 7; a good diagnostic points at the extra argument 9 on line 7.

module peg(h, r = 1) {
    cylinder(h = h, r = r);
}

peg(5, 2, 9);
