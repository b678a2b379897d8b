// A table: a top, a middle shelf and four legs (paper style: a unit primitive per part, placed by translate and scale).

// table top
translate([0, 0, 16.5]) scale([45, 45, 3]) cube(1, center=true);
// table middle
translate([0, 0, -11]) scale([41, 41, 3]) cube(1, center=true);
// left back leg
translate([-18.5, 18.5, -12.5]) scale([4, 4, 55]) cube(1, center=true);
// right back leg
translate([18.5, 18.5, -12.5]) scale([4, 4, 55]) cube(1, center=true);
// left front leg
translate([-18.5, -18.5, -12.5]) scale([4, 4, 55]) cube(1, center=true);
// right front leg
translate([18.5, -18.5, -12.5]) scale([4, 4, 55]) cube(1, center=true);
