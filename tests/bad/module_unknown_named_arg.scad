// Argument error: user module 'post' has no parameter 'height' (it is 'h'), named argument on line 7; a good diagnostic names 'height' and points at line 7, maybe listing post's parameters (w, h).

module post(w, h = 10) {
    cube([w, w, h]);
}

post(2, height = 20);
