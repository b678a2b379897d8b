// Exercises trig built-ins in degrees: sin cos tan asin acos atan atan2, results used as sizes, positions and rotation angles.

r = 20;
// a ring of cubes placed with sin and cos
for (ang = [0 : 90 : 270])
    translate([r * cos(ang), r * sin(ang), 0]) cube(2, center = true);
s = 10 * tan(45);                  // 10
translate([0, 0, 10]) cube([s, 2, 2]);
a1 = asin(0.5);                    // 30
a2 = acos(0.5);                    // 60
a3 = atan(1);                      // 45
a4 = atan2(1, 1);                  // 45
translate([0, 0, 20]) rotate(a1) cube([a2 / 10, 2, 2]);        // rotated 30 degrees, [6, 2, 2]
translate([0, 0, 30]) rotate([0, 0, a3 + a4]) cube([4, 2, 2]); // rotated 90 degrees
