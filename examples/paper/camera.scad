// A camera: body, grip, lens along the y axis and flash (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 40, 0]) scale([100, 20, 60]) cube(1, center=true);
// grip
translate([-37.5, 20, 0]) scale([25, 20, 60]) cube(1, center=true);
// lens
translate([12.5, 5, 0]) scale([50, 50, 50]) rotate([90, 0, 0]) cylinder(h=1, r=0.5, center=true);
// flash
translate([12.5, 40, 35]) scale([30, 20, 10]) cube(1, center=true);
