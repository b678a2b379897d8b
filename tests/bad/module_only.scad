// A file that only defines modules draws nothing; a good diagnostic lists chair and stool with their parameters and shows --call.
module leg(h, s) {
    cube([s, s, h]);
}

module chair(seat_w = 40, seat_d = 38, seat_h = 45, leg_s = 4) {
    for (x = [0, seat_w - leg_s], y = [0, seat_d - leg_s])
        translate([x, y, 0]) leg(seat_h, leg_s);
    // seat
    translate([0, 0, seat_h]) cube([seat_w, seat_d, 3]);
    // back
    translate([0, seat_d - 3, seat_h + 3]) cube([seat_w, 3, 40]);
}

module stool(h = 60) {
    cylinder(h = h, r = 15);
}
