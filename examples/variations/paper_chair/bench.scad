// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-77, -19.5, -22.5]) scale([6, 6, 45]) cube(1, center=true);
// right front leg
translate([77, -19.5, -22.5]) scale([6, 6, 45]) cube(1, center=true);
// left back leg
translate([-77, 19.5, -22.5]) scale([6, 6, 45]) cube(1, center=true);
// right back leg
translate([77, 19.5, -22.5]) scale([6, 6, 45]) cube(1, center=true);
// seat
translate([0, 0, 2.5]) scale([160, 45, 5]) cube(1, center=true);
// back
translate([0, 19.5, 25]) scale([160, 6, 40]) cube(1, center=true);
// left arm
translate([-80, -22.5, 5]) scale([0, 0, 0]) cube(1, center=true);
// right arm
translate([74, -22.5, 5]) scale([0, 0, 0]) cube(1, center=true);
