// A table: a top, a middle shelf and four legs (paper style: a unit primitive per part, placed by translate and scale).

// table top
translate([0, 0, 34]) scale([140, 70, 4]) cube(1, center=true);
// table middle
translate([0, 0, -2.5]) scale([136, 66, 3]) cube(1, center=true);
// left back leg
translate([-65, 30, -4]) scale([6, 6, 72]) cube(1, center=true);
// right back leg
translate([65, 30, -4]) scale([6, 6, 72]) cube(1, center=true);
// left front leg
translate([-65, -30, -4]) scale([6, 6, 72]) cube(1, center=true);
// right front leg
translate([65, -30, -4]) scale([6, 6, 72]) cube(1, center=true);
