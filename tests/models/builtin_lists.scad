// Exercises list/string built-ins len concat str, with their results used as sizes and positions.

v = [3, 4];
w = concat(v, [5]);                 // [3, 4, 5]
cube(w);
n = len(w);                         // 3
label = str("box", n, "-", 12);     // "box3-12"
translate([len(label) * 2, 0, 0]) cube([n, len("abcd"), 2]);   // at x = 14, [3, 4, 2]
nested = concat([[1, 2]], [[3, 4]], 7);   // [[1, 2], [3, 4], 7]
translate([0, 20, 0]) cube([len(nested), nested[1][1], nested[2]]);  // [3, 4, 7]
