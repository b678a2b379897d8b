// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-40, -37.5, -20]) scale([10, 10, 40]) cube(1, center=true);
// right front leg
translate([40, -37.5, -20]) scale([10, 10, 40]) cube(1, center=true);
// left back leg
translate([-40, 37.5, -20]) scale([10, 10, 40]) cube(1, center=true);
// right back leg
translate([40, 37.5, -20]) scale([10, 10, 40]) cube(1, center=true);
// seat
translate([0, 0, 6]) scale([90, 85, 12]) cube(1, center=true);
// back
translate([0, 37.5, 42]) scale([90, 10, 60]) cube(1, center=true);
// left arm
translate([-40, -5, 24.5]) scale([10, 75, 25]) cube(1, center=true);
// right arm
translate([40, -5, 24.5]) scale([10, 75, 25]) cube(1, center=true);
