// Exercises transforms nested 5 deep (translate, rotate, scale, mirror, translate) and a 4-deep chain of color/translate/rotate/translate.

translate([10, 0, 0])
    rotate([0, 0, 90])
        scale([2, 1, 1])
            mirror([1, 0, 0])
                translate([1, 2, 3])
                    cube([3, 2, 1]);

color("orange")
    translate([0, 30, 0])
        rotate([90, 0, 0])
            translate([0, 5, 0])
                cylinder(h = 4, r1 = 3, r2 = 2);
