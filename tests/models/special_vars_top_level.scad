// Exercises $fn, $fa and $fs assigned at top level: they apply to every cylinder and sphere below ($fn wins over $fa/$fs when nonzero).

$fa = 6;
$fs = 0.5;
$fn = 24;

cylinder(h = 10, r = 5);
translate([20, 0, 0]) sphere(r = 4);
