// A bottle: a cylindrical body, a conical shoulder and a cylindrical head (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 0, -25]) scale([60, 60, 50]) cylinder(h=1, r=0.5, center=true);
// body two (a cone narrowing upward)
translate([0, 0, 10]) scale([60, 60, 20]) cylinder(h=1, r1=0.5, r2=0.25, center=true);
// head
translate([0, 0, 25]) scale([25, 25, 10]) cylinder(h=1, r=0.5, center=true);
