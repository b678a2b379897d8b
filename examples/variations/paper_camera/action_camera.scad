// A camera: body, grip, lens along the y axis and flash (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 45, 0]) scale([60, 30, 45]) cube(1, center=true);
// grip
translate([-25, 27.5, 0]) scale([10, 5, 45]) cube(1, center=true);
// lens
translate([10, 25, 0]) scale([25, 10, 25]) rotate([90, 0, 0]) cylinder(h=1, r=0.5, center=true);
// flash
translate([10, 45, 24]) scale([10, 30, 3]) cube(1, center=true);
