// An unknown variable is undef: here a switch nobody set, so the arms are not drawn.
seat = 40;
cube([seat, seat, 5]);
if (show_arms) translate([0, 0, 5]) cube([5, seat, 20]);
translate([0, 0, height]) cube(2);
