// A table with a middle shelf, typed in part by part (same geometry as examples/paper/table.scad).

// table top
translate([-50, -50, 30]) cube([100, 100, 10]);
// table middle
translate([-45, -45, -5]) cube([90, 90, 10]);
// left back leg
translate([-45, 35, -40]) cube([10, 10, 70]);
// right back leg
translate([35, 35, -40]) cube([10, 10, 70]);
// left front leg
translate([-45, -45, -40]) cube([10, 10, 70]);
// right front leg
translate([35, -45, -40]) cube([10, 10, 70]);
