// A camera: body, grip, lens along the y axis and flash (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 42.5, 0]) scale([100, 25, 60]) cube(1, center=true);
// grip
translate([-42.5, 26, 0]) scale([15, 8, 60]) cube(1, center=true);
// lens
translate([20, 20, 0]) scale([35, 20, 35]) rotate([90, 0, 0]) cylinder(h=1, r=0.5, center=true);
// flash
translate([20, 42.5, 33]) scale([20, 25, 6]) cube(1, center=true);
