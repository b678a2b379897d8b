// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-45, -42.5, -40]) cube([10, 10, 40]);
// right front leg
translate([35, -42.5, -40]) cube([10, 10, 40]);
// left back leg
translate([-45, 32.5, -40]) cube([10, 10, 40]);
// right back leg
translate([35, 32.5, -40]) cube([10, 10, 40]);
// seat
translate([-45, -42.5, 0]) cube([90, 85, 12]);
// back
translate([-45, 32.5, 12]) cube([90, 10, 60]);
// left arm
translate([-45, -42.5, 12]) cube([10, 75, 25]);
// right arm
translate([35, -42.5, 12]) cube([10, 75, 25]);
