// Exercises children(): all children, children(i) by index, $children, children() under a transform, and a range of children.

module stack(gap = 10) {
    // place each child above the previous one
    for (i = [0 : $children - 1])
        translate([0, 0, i * gap]) children(i);
}

module second_only() {
    children(1);
}

module shifted_all() {
    translate([50, 0, 0]) children();
}

module count_marker() {
    // a cube whose size is the number of children
    translate([0, -20, 0]) cube($children);
    children([0 : 1]);
}

stack() {
    cube(4);
    sphere(r = 3);
    cylinder(h = 5, r = 2);
}
second_only() {
    cube(100);           // not drawn
    translate([20, 0, 0]) cube(6);
}
shifted_all() {
    cube(2);
    translate([0, 5, 0]) cube(3);
}
count_marker() {
    translate([80, 0, 0]) cube(1);
    translate([90, 0, 0]) cube(2);
    translate([100, 0, 0]) cube(3);   // not drawn
}
