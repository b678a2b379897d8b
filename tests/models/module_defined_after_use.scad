// Exercises a module and a function used before their definitions appear in the file (both are hoisted).

peg(3);
translate([10, 0, 0]) peg(height_for(2));

module peg(h) {
    cylinder(h = h, r = 1);
    translate([0, 0, h]) sphere(r = 1.5);
}

function height_for(n) = n * 4;
