// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-50, -50, -70]) cube([15, 15, 70]);
// right front leg
translate([35, -50, -70]) cube([15, 15, 70]);
// left back leg
translate([-50, 35, -70]) cube([15, 15, 70]);
// right back leg
translate([35, 35, -70]) cube([15, 15, 70]);
// seat
translate([-50, -50, 0]) cube([100, 100, 15]);
// back
translate([-50, 35, 15]) cube([100, 15, 70]);
// left arm
translate([-50, -50, 15]) cube([15, 85, 30]);
// right arm
translate([35, -50, 15]) cube([15, 85, 30]);
