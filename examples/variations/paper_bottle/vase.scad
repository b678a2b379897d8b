// A bottle: a cylindrical body, a conical shoulder and a cylindrical head (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 0, -30]) scale([50, 50, 40]) cylinder(h=1, r=0.5, center=true);
// body two (a cone narrowing upward)
translate([0, 0, 10]) scale([50, 50, 40]) cylinder(h=1, r1=0.5, r2=0.3, center=true);
// head
translate([0, 0, 37.5]) scale([30, 30, 15]) cylinder(h=1, r=0.5, center=true);
