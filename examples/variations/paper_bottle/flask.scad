// A bottle: a cylindrical body, a conical shoulder and a cylindrical head (paper style: a unit primitive per part, placed by translate and scale).

// body
translate([0, 0, -35]) scale([40, 40, 30]) cylinder(h=1, r=0.5, center=true);
// body two (a cone narrowing upward)
translate([0, 0, -7.5]) scale([40, 40, 25]) cylinder(h=1, r1=0.5, r2=0.2, center=true);
// head
translate([0, 0, 15]) scale([15, 15, 20]) cylinder(h=1, r=0.5, center=true);
