// Library of default dimensions, meant to be included and then overridden (see assignment_override_include.scad).
plate_w = 30;
plate_d = 20;
plate_t = 2;
plate_area_side = plate_w + plate_d;   // recomputed from the final plate_w and plate_d
