// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-18, -18, -50]) scale([4, 4, 100]) cube(1, center=true);
// right front leg
translate([18, -18, -50]) scale([4, 4, 100]) cube(1, center=true);
// left back leg
translate([-18, 18, -50]) scale([4, 4, 100]) cube(1, center=true);
// right back leg
translate([18, 18, -50]) scale([4, 4, 100]) cube(1, center=true);
// seat
translate([0, 0, 2]) scale([40, 40, 4]) cube(1, center=true);
// back
translate([-20, 16, 4]) scale([0, 0, 0]) cube(1, center=true);
// left arm
translate([-20, -20, 4]) scale([0, 0, 0]) cube(1, center=true);
// right arm
translate([16, -20, 4]) scale([0, 0, 0]) cube(1, center=true);
