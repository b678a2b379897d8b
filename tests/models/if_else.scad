// Exercises if, if/else, else if chains, and if without braces, choosing which primitives are drawn.

style = 2;
big = true;

if (big) cube(10); else cube(1);

if (style == 1) {
    translate([20, 0, 0]) sphere(r = 3);
} else if (style == 2) {
    translate([20, 0, 0]) cylinder(h = 6, r = 3);   // this one
} else {
    translate([20, 0, 0]) cube(3);
}

for (i = [0 : 3])
    if (i % 2 == 0)
        translate([i * 10, 20, 0]) cube(2);
    else
        translate([i * 10, 20, 0]) sphere(r = 1);

if (!big) translate([0, 40, 0]) cube(5);   // nothing drawn
