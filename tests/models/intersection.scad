// Exercises intersection of a cube and a sphere (a rounded cube) and of three perpendicular cylinders.

intersection() {
    cube(20, center = true);
    sphere(r = 13);
}
translate([50, 0, 0]) intersection() {
    cylinder(h = 20, r = 8, center = true);
    rotate([90, 0, 0]) cylinder(h = 20, r = 8, center = true);
    rotate([0, 90, 0]) cylinder(h = 20, r = 8, center = true);
}
