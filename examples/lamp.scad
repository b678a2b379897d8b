// A desk lamp: a round base with a cord hole, a jointed arm of rotated rods, a ball joint and a conical shade.

base_r = 30;
base_h = 5;
arm_r = 2;
arm1 = 60;
arm2 = 50;
tilt = 90;           // the second arm is turned by a multiple of 90 degrees

// base plate with a hole for the cord
difference() {
    // base disc
    color("dimgray") cylinder(h = base_h, r = base_r);
    // cord hole through the base, along x
    translate([base_r - 10, 0, base_h / 2])
        rotate([0, tilt, 0]) cylinder(h = 30, r = 1.5, center = true);
}

// lower arm, straight up
translate([0, 0, base_h]) {
    color("silver") cylinder(h = arm1, r = arm_r);
    // elbow joint
    translate([0, 0, arm1]) {
        color("black") sphere(d = 3 * arm_r);
        // upper arm, turned onto +x
        rotate([0, tilt, 0]) {
            color("silver") cylinder(h = arm2, r = arm_r);
            // shade: a cone opening downward, hanging at the end of the arm
            translate([0, 0, arm2])
                rotate([0, -tilt, 0])
                    translate([0, 0, -20])
                        color("green", 0.8) cylinder(h = 20, r1 = 18, r2 = 6);
        }
    }
}
