// A car: three chassis blocks and four wheels on the x axis (paper style: a unit primitive per part, placed by translate and scale).

// back chassis
translate([0, 75, -3.5]) scale([100, 50, 28]) cube(1, center=true);
// mid chassis
translate([0, 5, 5]) scale([100, 90, 45]) cube(1, center=true);
// front chassis
translate([0, -70, -3.5]) scale([100, 60, 28]) cube(1, center=true);
// left back wheel
translate([-55, 50, -17.5]) scale([10, 30, 30]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right back wheel
translate([55, 50, -17.5]) scale([10, 30, 30]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// left front wheel
translate([-55, -70, -17.5]) scale([10, 30, 30]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
// right front wheel
translate([55, -70, -17.5]) scale([10, 30, 30]) rotate([0, 90, 0]) cylinder(h=1, r=0.5, center=true);
