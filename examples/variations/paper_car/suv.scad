// A car: three chassis blocks and four wheels on the x axis (paper style: a unit primitive per part, placed by translate and scale).

// back chassis
translate([0, 77.5, 2.5]) scale([110, 30, 40]) cube(1, center=true);
// mid chassis
translate([0, 7.5, 20]) scale([110, 110, 75]) cube(1, center=true);
// front chassis
translate([0, -70, 2.5]) scale([110, 45, 40]) cube(1, center=true);
// left back wheel
translate([-61, 62.5, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right back wheel
translate([61, 62.5, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// left front wheel
translate([-61, -70, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right front wheel
translate([61, -70, -17.5]) scale([12, 40, 40]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
