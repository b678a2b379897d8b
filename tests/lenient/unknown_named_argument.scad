// A named argument the module does not declare: OpenSCAD warns and sets it inside the module all the same.
module post(w, h = 10) {
    cube([w, w, h]);
    translate([0, 0, h]) cube([w, w, cap]);
}
post(2, cap = 1);
