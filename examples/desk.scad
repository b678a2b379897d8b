// A writing desk with a drawer unit, built from a parameterized leg module and named arguments.

desk_width = 120;
desk_depth = 60;
desk_height = 75;
top_thickness = 3;
leg = 5;

// a square table leg of a given height, optionally with a rubber foot
module leg(height, size = 5, foot = true) {
    // leg post
    translate([0, 0, foot ? 1 : 0]) cube([size, size, height - (foot ? 1 : 0)]);
    // rubber foot
    if (foot)
        translate([size / 2, size / 2, 0]) cylinder(h = 1, r = size / 2 + 0.5);
}

// a drawer front with a round knob in the middle
module drawer(w, h, knob_r = 1.5) {
    // drawer front panel
    color("burlywood") cube([w, 2, h]);
    // knob
    translate([w / 2, 0, h / 2]) color("silver") sphere(r = knob_r);
}

// desk top
color("saddlebrown")
    translate([0, 0, desk_height - top_thickness])
        cube([desk_width, desk_depth, top_thickness]);

// four legs, placed by a loop over the corner positions
for (pos = [[0, 0], [desk_width - leg, 0], [0, desk_depth - leg], [desk_width - leg, desk_depth - leg]])
    translate([pos[0], pos[1], 0])
        leg(height = desk_height - top_thickness, size = leg);

// modesty panel across the back
translate([leg, desk_depth - leg / 2 - 1, 30])
    cube([desk_width - 2 * leg, 2, desk_height - top_thickness - 30]);

// drawer unit hanging under the top, on the right
drawer_w = 40;
drawer_h = 12;
translate([desk_width - leg - drawer_w, 0, desk_height - top_thickness - 2 * drawer_h])
    for (k = [0 : 1])
        translate([0, 0, k * drawer_h])
            drawer(drawer_w, drawer_h - 1);
