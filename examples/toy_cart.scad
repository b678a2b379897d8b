// A toy cart: a box body on a deck, two axles with wheels turned onto the x axis, a handle bar.

deck = [60, 100, 4];          // deck size
wall = 3;                     // wall thickness of the box
box_h = 25;
wheel_r = 12;
wheel_w = 6;
axle_r = 2;
axle_y = [15, 85];            // axle positions along the cart

// a wheel of given radius and width, centered on the origin, turned onto the x axis
module wheel(r = 10, w = 5) {
    rotate([0, 90, 0]) {
        // tyre
        color("black") cylinder(h = w, r = r, center = true);
        // hub cap, a small cone sticking out
        translate([0, 0, w / 2]) color("red") cylinder(h = 2, r1 = r / 3, r2 = r / 5);
    }
}

// an axle with a wheel at each end
module axle(length, r = 2) {
    // axle rod along x
    rotate([0, 90, 0]) cylinder(h = length, r = r, center = true);
    // one wheel on each side; the second is the first mirrored across x = 0
    for (side = [0, 1])
        mirror([side, 0, 0])
            translate([length / 2 + wheel_w / 2, 0, 0])
                wheel(r = wheel_r, w = wheel_w);
}

// deck
color("yellow") translate([-deck.x / 2, 0, wheel_r]) cube(deck);

// open box on the deck: outer box minus inner box
translate([0, deck.y / 2, wheel_r + deck.z + box_h / 2])
    difference() {
        // outer walls
        cube([deck.x, deck.y, box_h], center = true);
        // hollow, open at the top
        translate([0, 0, wall])
            cube([deck.x - 2 * wall, deck.y - 2 * wall, box_h], center = true);
    }

// axles with wheels
for (y = axle_y)
    translate([0, y, wheel_r])
        axle(length = deck.x + 2, r = axle_r);

// handle bar at the front, a rod with a ball on the end
translate([0, 0, wheel_r + deck.z / 2]) rotate([90, 0, 0]) {
    // handle rod
    cylinder(h = 40, r = 1.5);
    // handle ball
    translate([0, 0, 40]) sphere(r = 4);
}
