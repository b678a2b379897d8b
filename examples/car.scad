// A toy car: three chassis blocks and four wheels turned onto the x axis (same geometry as examples/paper/car.scad).

// back chassis
translate([-50, 50, -17.5]) cube([100, 25, 30]);
// mid chassis
translate([-50, -25, -17.5]) cube([100, 75, 50]);
// front chassis
translate([-50, -75, -17.5]) cube([100, 50, 30]);
// left back wheel
translate([-55, 50, -17.5]) rotate([0, 90, 0]) cylinder(h=10, r=15, center=true);
// right back wheel
translate([55, 50, -17.5]) rotate([0, 90, 0]) cylinder(h=10, r=15, center=true);
// left front wheel
translate([-55, -50, -17.5]) rotate([0, 90, 0]) cylinder(h=10, r=15, center=true);
// right front wheel
translate([55, -50, -17.5]) rotate([0, 90, 0]) cylinder(h=10, r=15, center=true);
