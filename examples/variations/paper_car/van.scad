// A car: three chassis blocks and four wheels on the x axis (paper style: a unit primitive per part, placed by translate and scale).

// back chassis
translate([0, 90, 2.5]) scale([110, 20, 40]) cube(1, center=true);
// mid chassis
translate([0, 5, 27.5]) scale([110, 150, 90]) cube(1, center=true);
// front chassis
translate([0, -85, 2.5]) scale([110, 30, 40]) cube(1, center=true);
// left back wheel
translate([-60, 80, -17.5]) scale([10, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right back wheel
translate([60, 80, -17.5]) scale([10, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// left front wheel
translate([-60, -85, -17.5]) scale([10, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right front wheel
translate([60, -85, -17.5]) scale([10, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
