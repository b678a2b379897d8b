// A camera: a body, a grip, a lens pointing along -y and a flash (same geometry as examples/paper/camera.scad).

// body
translate([-50, 30, -30]) cube([100, 20, 60]);
// grip
translate([-50, 10, -30]) cube([25, 20, 60]);
// lens, a cylinder turned from z onto +y, starting at y = -20
translate([12.5, -20, 0]) rotate([-90, 0, 0]) cylinder(h=50, r=25);
// flash
translate([-2.5, 30, 30]) cube([30, 20, 10]);
