// A table: a top, a middle shelf and four legs (paper style: a unit primitive per part, placed by translate and scale).

// table top
translate([0, 0, 34.5]) scale([180, 90, 5]) cube(1, center=true);
// table middle
translate([0, 0, -2]) scale([172, 82, 4]) cube(1, center=true);
// left back leg
translate([-82, 37, -4]) scale([8, 8, 72]) cube(1, center=true);
// right back leg
translate([82, 37, -4]) scale([8, 8, 72]) cube(1, center=true);
// left front leg
translate([-82, -37, -4]) scale([8, 8, 72]) cube(1, center=true);
// right front leg
translate([82, -37, -4]) scale([8, 8, 72]) cube(1, center=true);
