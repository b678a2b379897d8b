// A chair: four legs, a seat, a back and two arms (paper style: a unit primitive per part, placed by translate and scale).

// left front leg
translate([-36, -51, -12.5]) scale([8, 8, 25]) cube(1, center=true);
// right front leg
translate([36, -51, -12.5]) scale([8, 8, 25]) cube(1, center=true);
// left back leg
translate([-36, 51, -12.5]) scale([8, 8, 25]) cube(1, center=true);
// right back leg
translate([36, 51, -12.5]) scale([8, 8, 25]) cube(1, center=true);
// seat
translate([0, 0, 5]) scale([80, 110, 10]) cube(1, center=true);
// back
translate([0, 51, 35]) scale([80, 8, 50]) cube(1, center=true);
// left arm
translate([-36, -4, 20]) scale([8, 102, 20]) cube(1, center=true);
// right arm
translate([36, -4, 20]) scale([8, 102, 20]) cube(1, center=true);
