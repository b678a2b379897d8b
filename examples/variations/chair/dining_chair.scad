// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-22.5, -22.5, -45]) cube([4, 4, 45]);
// right front leg
translate([18.5, -22.5, -45]) cube([4, 4, 45]);
// left back leg
translate([-22.5, 18.5, -45]) cube([4, 4, 45]);
// right back leg
translate([18.5, 18.5, -45]) cube([4, 4, 45]);
// seat
translate([-22.5, -22.5, 0]) cube([45, 45, 4]);
// back
translate([-22.5, 18.5, 4]) cube([45, 4, 45]);
// left arm
translate([-22.5, -22.5, 4]) cube([0, 0, 0]);
// right arm
translate([18.5, -22.5, 4]) cube([0, 0, 0]);
