// A chair, typed in part by part (same geometry as examples/paper/chair.scad).

// left front leg
translate([-20, -20, -100]) cube([4, 4, 100]);
// right front leg
translate([16, -20, -100]) cube([4, 4, 100]);
// left back leg
translate([-20, 16, -100]) cube([4, 4, 100]);
// right back leg
translate([16, 16, -100]) cube([4, 4, 100]);
// seat
translate([-20, -20, 0]) cube([40, 40, 4]);
// back
translate([-20, 16, 4]) cube([0, 0, 0]);
// left arm
translate([-20, -20, 4]) cube([0, 0, 0]);
// right arm
translate([16, -20, 4]) cube([0, 0, 0]);
