// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-35, -50, -12.5]) scale([10, 10, 25]) cube(1, center=true);
// right front leg
translate([35, -50, -12.5]) scale([10, 10, 25]) cube(1, center=true);
// left back leg
translate([-35, 50, -12.5]) scale([10, 10, 25]) cube(1, center=true);
// right back leg
translate([35, 50, -12.5]) scale([10, 10, 25]) cube(1, center=true);
// seat
translate([0, 0, 5]) scale([80, 110, 10]) cube(1, center=true);
// back
translate([0, 50, 35]) scale([80, 10, 50]) cube(1, center=true);
// left arm
translate([-35, -5, 20]) scale([10, 100, 20]) cube(1, center=true);
// right arm
translate([35, -5, 20]) scale([10, 100, 20]) cube(1, center=true);
