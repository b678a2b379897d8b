// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-80, -22.5, -45]) cube([6, 6, 45]);
// right front leg
translate([74, -22.5, -45]) cube([6, 6, 45]);
// left back leg
translate([-80, 16.5, -45]) cube([6, 6, 45]);
// right back leg
translate([74, 16.5, -45]) cube([6, 6, 45]);
// seat
translate([-80, -22.5, 0]) cube([160, 45, 5]);
// back
translate([-80, 16.5, 5]) cube([160, 6, 40]);
// left arm
translate([-80, -22.5, 5]) cube([0, 0, 0]);
// right arm
translate([74, -22.5, 5]) cube([0, 0, 0]);
