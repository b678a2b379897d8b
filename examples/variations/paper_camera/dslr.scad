// A camera: body, grip, lens along the y axis and flash (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 50, 0]) scale([130, 40, 95]) cube(1, center=true);
// grip
translate([-47.5, 15, 0]) scale([35, 30, 95]) cube(1, center=true);
// lens
translate([10, -10, 0]) scale([70, 80, 70]) rotate([90, 0, 0]) cylinder(h=1, r=0.5, center=true);
// flash
translate([10, 50, 57.5]) scale([35, 40, 20]) cube(1, center=true);
