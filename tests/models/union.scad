// Exercises union explicitly (with several children) and implicitly (a block under a transform), with overlapping parts.

union() {
    cube([20, 5, 5]);
    translate([0, 0, 5]) cube([5, 5, 15]);
    translate([15, 2.5, 5]) cylinder(h = 10, r = 2.5);
}
translate([0, 20, 0]) {
    sphere(r = 4);
    cube(4);
}
