// Exercises color by name, by name with alpha, by RGB vector, by RGBA vector, by hex string, named c= and alpha= arguments, and nested colors.

color("red") cube(5);
translate([10, 0, 0]) color("blue", 0.5) cube(5);
translate([20, 0, 0]) color([0, 1, 0]) sphere(r = 3);
translate([30, 0, 0]) color([1, 0.5, 0, 0.25]) cylinder(h = 5, r = 2);
translate([40, 0, 0]) color("#ff00ff") cube(4);
translate([50, 0, 0]) color(c = "Gold", alpha = 0.8) cube(4);
translate([60, 0, 0]) color("green") { cube(3); color("yellow") translate([0, 0, 5]) cube(2); }
