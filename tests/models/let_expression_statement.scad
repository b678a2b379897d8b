// Exercises let: as an expression (sequential bindings, later ones see earlier ones) and as a statement scoping variables over child geometry.

w = let (a = 4, b = a * 2) a + b;            // 12
cube([w, 3, 3]);

let (x = 20, y = x / 2) {
    translate([x, y, 0]) cube([y, 2, 2]);     // at [20, 10, 0], size [10, 2, 2]
    translate([0, 0, x]) sphere(r = y / 5);   // at z = 20, r = 2
}

// a let statement that shadows an outer variable
let (w = 5) translate([0, 30, 0]) cube(w);    // cube(5), not 12
