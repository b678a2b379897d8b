// A car: three chassis blocks and four wheels on the x axis (paper style: a unit primitive per part, placed by translate and scale).

// back chassis
translate([0, 70, -7.5]) scale([105, 50, 20]) cube(1, center=true);
// mid chassis
translate([0, 10, 0]) scale([105, 70, 35]) cube(1, center=true);
// front chassis
translate([0, -60, -7.5]) scale([105, 70, 20]) cube(1, center=true);
// left back wheel
translate([-58.5, 45, -17.5]) scale([12, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right back wheel
translate([58.5, 45, -17.5]) scale([12, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// left front wheel
translate([-58.5, -60, -17.5]) scale([12, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right front wheel
translate([58.5, -60, -17.5]) scale([12, 32, 32]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
