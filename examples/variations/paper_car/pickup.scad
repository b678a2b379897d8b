// A car: three chassis blocks and four wheels on the x axis (paper style: a unit primitive per part, placed by translate and scale).

// back chassis
translate([0, 60, 0]) scale([110, 90, 35]) cube(1, center=true);
// mid chassis
translate([0, -15, 17.5]) scale([110, 60, 70]) cube(1, center=true);
// front chassis
translate([0, -75, 0]) scale([110, 60, 35]) cube(1, center=true);
// left back wheel
translate([-61, 15, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right back wheel
translate([61, 15, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// left front wheel
translate([-61, -75, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right front wheel
translate([61, -75, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
