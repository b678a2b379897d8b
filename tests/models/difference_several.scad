// Exercises difference with several subtrahends: a plate minus four corner holes (from a loop), a center hole and a slot.

difference() {
    // plate
    cube([60, 40, 5]);
    // corner holes
    for (p = [[6, 6], [54, 6], [6, 34], [54, 34]])
        translate([p[0], p[1], -1]) cylinder(h = 7, r = 2);
    // center hole
    translate([30, 20, -1]) cylinder(h = 7, d = 10);
    // slot
    translate([20, 30, -1]) cube([20, 3, 7]);
}
