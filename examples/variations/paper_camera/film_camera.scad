// A camera: body, grip, lens along the y axis and flash (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 45, 0]) scale([140, 30, 80]) cube(1, center=true);
// grip
translate([-57.5, 22.5, 0]) scale([25, 15, 80]) cube(1, center=true);
// lens
translate([0, 10, 0]) scale([45, 40, 45]) rotate([90, 0, 0]) cylinder(h=1, r=0.5, center=true);
// flash
translate([0, 45, 47.5]) scale([30, 30, 15]) cube(1, center=true);
