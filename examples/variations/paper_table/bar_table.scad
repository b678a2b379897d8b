// A table: a top, a middle shelf and four legs (paper style: a unit primitive per part, placed by translate and scale).

// table top
translate([0, 0, 67]) scale([60, 60, 4]) cube(1, center=true);
// table middle
translate([0, 0, 14.5]) scale([50, 50, 4]) cube(1, center=true);
// left back leg
translate([-22, 22, 12.5]) scale([6, 6, 105]) cube(1, center=true);
// right back leg
translate([22, 22, 12.5]) scale([6, 6, 105]) cube(1, center=true);
// left front leg
translate([-22, -22, 12.5]) scale([6, 6, 105]) cube(1, center=true);
// right front leg
translate([22, -22, 12.5]) scale([6, 6, 105]) cube(1, center=true);
