// Exercises intersection_for: the intersection of a cube rotated by 0, 30 and 60 degrees about z.

intersection_for (a = [0 : 30 : 60])
    rotate([0, 0, a]) cube([20, 20, 5], center = true);
