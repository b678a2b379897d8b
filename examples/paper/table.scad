// A table: a top, a middle shelf and four legs (paper style: a unit primitive per part, placed by translate and scale).

// table top
translate([0, 0, 35]) scale([100, 100, 10]) cube(1, center=true);
// table middle
translate([0, 0, 0]) scale([90, 90, 10]) cube(1, center=true);
// left back leg
translate([-40, 40, -5]) scale([10, 10, 70]) cube(1, center=true);
// right back leg
translate([40, 40, -5]) scale([10, 10, 70]) cube(1, center=true);
// left front leg
translate([-40, -40, -5]) scale([10, 10, 70]) cube(1, center=true);
// right front leg
translate([40, -40, -5]) scale([10, 10, 70]) cube(1, center=true);
