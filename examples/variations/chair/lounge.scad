// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-40, -55, -25]) cube([8, 8, 25]);
// right front leg
translate([32, -55, -25]) cube([8, 8, 25]);
// left back leg
translate([-40, 47, -25]) cube([8, 8, 25]);
// right back leg
translate([32, 47, -25]) cube([8, 8, 25]);
// seat
translate([-40, -55, 0]) cube([80, 110, 10]);
// back
translate([-40, 47, 10]) cube([80, 8, 50]);
// left arm
translate([-40, -55, 10]) cube([8, 102, 20]);
// right arm
translate([32, -55, 10]) cube([8, 102, 20]);
