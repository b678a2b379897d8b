// A loop that would make ten million parts (line 3); a good diagnostic stops it within seconds and points into line 3.

for (i = [0 : 1e7]) translate([i, 0, 0]) cube(1);
