// A bottle: body, conical shoulder and head stacked along z (same geometry as examples/paper/bottle.scad).

// body
translate([0, 0, -50]) cylinder(h=40, r=20);
// shoulder (body2 in the paper), a cone narrowing from radius 20 to 8
translate([0, 0, -10]) cylinder(h=30, r1=20, r2=8);
// head
translate([0, 0, 20]) cylinder(h=20, r=10);
