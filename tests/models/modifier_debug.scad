// Exercises the # (debug/highlight) modifier: the cylinder is highlighted but still part of the result, here inside a difference.

difference() {
    cube(20, center = true);
    #cylinder(h = 30, r = 5, center = true);
}
