// Exercises mirror([1, 0, 0]): a cube and a sphere reflected across the plane x = 0, next to an unmirrored copy.

module part() {
    translate([10, 0, 0]) cube([5, 3, 2]);
    translate([20, 0, 0]) sphere(r = 2);
}

part();
mirror([1, 0, 0]) part();     // cube at x in [-15, -10], sphere at x = -20
mirror(v = [0, 1, 0]) translate([0, 10, 0]) cube(2);   // named v, reflected across y = 0
