// A four-legged bar stool: variables at the top, legs placed by a for loop, rungs turned by a loop variable.

// overall dimensions
seat_size = 40;       // square seat, side length
seat_thickness = 4;
seat_height = 70;     // top of the seat above the floor
leg_size = 4;         // square legs
inset = 3;            // legs are set in from the seat edge
rung_height = 25;
rung_size = 2;

leg_height = seat_height - seat_thickness;
half = seat_size / 2 - inset - leg_size / 2;   // leg center offset from the middle

// legs, one at each corner, placed by a loop over corner positions
for (p = [[-1, -1], [1, -1], [-1, 1], [1, 1]])
    translate([p[0] * half, p[1] * half, leg_height / 2])
        cube([leg_size, leg_size, leg_height], center=true);

// seat
translate([0, 0, leg_height + seat_thickness / 2])
    cube([seat_size, seat_size, seat_thickness], center=true);

// footrest rungs on all four sides, turned by multiples of 90 degrees
for (i = [0 : 3])
    rotate(i * 90)
        translate([0, half, rung_height])
            cube([2 * half, rung_size, rung_size], center=true);
