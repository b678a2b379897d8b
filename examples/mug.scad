// A coffee mug: a difference of cylinders for the cup and a handle made of boxes.

height = 95;
outer_r = 40;
wall = 4;
bottom = 5;
handle_gap = 25;     // how far the handle stands off the side
handle_t = 8;        // handle bar thickness

// cup: outer cylinder minus the inside
color([0.9, 0.9, 0.85])
difference() {
    // outer wall
    cylinder(h = height, r = outer_r);
    // inside, open at the top
    translate([0, 0, bottom]) cylinder(h = height, r = outer_r - wall);
}

// handle, built from three bars on the +x side
module handle(gap, t, span = 60) {
    // upper arm
    translate([0, -t / 2, span]) cube([gap + t, t, t]);
    // lower arm
    translate([0, -t / 2, 0]) cube([gap + t, t, t]);
    // grip
    translate([gap, -t / 2, 0]) cube([t, t, span + t]);
}

translate([outer_r - wall / 2, 0, (height - 60) / 2 - handle_t / 2])
    handle(handle_gap, handle_t);
