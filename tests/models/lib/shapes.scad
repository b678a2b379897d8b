// Library for include_file.scad and use_file.scad: a variable, a function, two modules, and top-level geometry (drawn by include, not by use).

lib_wall = 2;

function lib_double(x) = 2 * x;

// a hollow square tube of outer side s and height h, with wall lib_wall
module lib_tube(s = 10, h = 20) {
    difference() {
        cube([s, s, h]);
        translate([lib_wall, lib_wall, -1]) cube([s - 2 * lib_wall, s - 2 * lib_wall, h + 2]);
    }
}

// a peg: a cylinder with a ball on top
module lib_peg(h = 8, r = 1.5) {
    cylinder(h = h, r = r);
    translate([0, 0, h]) sphere(r = r * 1.5);
}

// top-level geometry of the library: a marker cube at [-30, -30, 0]
translate([-30, -30, 0]) cube(3);
