// Library that itself includes another library (for include_nested.scad): a module built on lib_peg from shapes.scad.

include <shapes.scad>

module lib_peg_row(n = 3, gap = 6) {
    for (i = [0 : n - 1]) translate([i * gap, 0, 0]) lib_peg();
}
