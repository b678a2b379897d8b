// A workbench calls its module with more arguments than it declares: OpenSCAD warns and ignores the extra one.
module leg(h, w = 4) {
    cube([w, w, h]);
}
translate([0, 0, 0]) leg(40, 4, 5);
translate([60, 0, 0]) leg(40, 4, 5);
translate([0, 0, 40]) cube([64, 30, 3]);
