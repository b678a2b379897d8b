// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-20.5, -20.5, -22.5]) scale([4, 4, 45]) cube(1, center=true);
// right front leg
translate([20.5, -20.5, -22.5]) scale([4, 4, 45]) cube(1, center=true);
// left back leg
translate([-20.5, 20.5, -22.5]) scale([4, 4, 45]) cube(1, center=true);
// right back leg
translate([20.5, 20.5, -22.5]) scale([4, 4, 45]) cube(1, center=true);
// seat
translate([0, 0, 2]) scale([45, 45, 4]) cube(1, center=true);
// back
translate([0, 20.5, 26.5]) scale([45, 4, 45]) cube(1, center=true);
// left arm
translate([-22.5, -22.5, 4]) scale([0, 0, 0]) cube(1, center=true);
// right arm
translate([18.5, -22.5, 4]) scale([0, 0, 0]) cube(1, center=true);
