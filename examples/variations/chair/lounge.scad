// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-40, -55, -25]) cube([10, 10, 25]);
// right front leg
translate([30, -55, -25]) cube([10, 10, 25]);
// left back leg
translate([-40, 45, -25]) cube([10, 10, 25]);
// right back leg
translate([30, 45, -25]) cube([10, 10, 25]);
// seat
translate([-40, -55, 0]) cube([80, 110, 10]);
// back
translate([-40, 45, 10]) cube([80, 10, 50]);
// left arm
translate([-40, -55, 10]) cube([10, 100, 20]);
// right arm
translate([30, -55, 10]) cube([10, 100, 20]);
