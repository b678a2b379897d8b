// A camera: body, grip, lens along the y axis and flash (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 52.5, 0]) scale([110, 45, 110]) cube(1, center=true);
// grip
translate([-45, 25, 0]) scale([20, 10, 110]) cube(1, center=true);
// lens
translate([20, 17.5, 0]) scale([50, 25, 50]) rotate([90, 0, 0]) cylinder(h=1, r=0.5, center=true);
// flash
translate([20, 52.5, 61]) scale([30, 45, 12]) cube(1, center=true);
