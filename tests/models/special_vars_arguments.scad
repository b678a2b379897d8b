// Exercises $fn, $fa and $fs passed as arguments to primitives and to a user module (where they flow down dynamically to its children).

module ring_of_posts(n = 4) {
    for (i = [0 : n - 1]) rotate(i * 360 / n) translate([15, 0, 0]) cylinder(h = 8, r = 2);
}

cylinder(h = 10, r = 5, $fn = 6);                     // a hexagonal prism
translate([0, 20, 0]) sphere(r = 4, $fa = 5, $fs = 0.2);
translate([0, 40, 0]) cylinder(h = 5, r = 3, $fs = 1);
translate([40, 0, 0]) ring_of_posts($fn = 8);         // every post gets $fn = 8
