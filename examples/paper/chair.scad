// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-42.5, -42.5, -35]) scale([15, 15, 70]) cube(1, center=true);
// right front leg
translate([42.5, -42.5, -35]) scale([15, 15, 70]) cube(1, center=true);
// left back leg
translate([-42.5, 42.5, -35]) scale([15, 15, 70]) cube(1, center=true);
// right back leg
translate([42.5, 42.5, -35]) scale([15, 15, 70]) cube(1, center=true);
// seat
translate([0, 0, 7.5]) scale([100, 100, 15]) cube(1, center=true);
// back
translate([0, 42.5, 50]) scale([100, 15, 70]) cube(1, center=true);
// left arm
translate([-42.5, -7.5, 30]) scale([15, 85, 30]) cube(1, center=true);
// right arm
translate([42.5, -7.5, 30]) scale([15, 85, 30]) cube(1, center=true);
