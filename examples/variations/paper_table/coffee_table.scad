// A table: a top, a middle shelf and four legs (paper style: a unit primitive per part, placed by translate and scale).

// table top
translate([0, 0, 2]) scale([120, 60, 4]) cube(1, center=true);
// table middle
translate([0, 0, -18.5]) scale([114, 54, 3]) cube(1, center=true);
// left back leg
translate([-54.5, 24.5, -20]) scale([5, 5, 40]) cube(1, center=true);
// right back leg
translate([54.5, 24.5, -20]) scale([5, 5, 40]) cube(1, center=true);
// left front leg
translate([-54.5, -24.5, -20]) scale([5, 5, 40]) cube(1, center=true);
// right front leg
translate([54.5, -24.5, -20]) scale([5, 5, 40]) cube(1, center=true);
