// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-45, -42.5, -40]) cube([12, 12, 40]);
// right front leg
translate([33, -42.5, -40]) cube([12, 12, 40]);
// left back leg
translate([-45, 30.5, -40]) cube([12, 12, 40]);
// right back leg
translate([33, 30.5, -40]) cube([12, 12, 40]);
// seat
translate([-45, -42.5, 0]) cube([90, 85, 12]);
// back
translate([-45, 30.5, 12]) cube([90, 12, 60]);
// left arm
translate([-45, -42.5, 12]) cube([12, 73, 25]);
// right arm
translate([33, -42.5, 12]) cube([12, 73, 25]);
