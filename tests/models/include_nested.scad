// Exercises an include of a library that includes another library (paths resolve relative to the including file): draws a row of pegs plus the inner library's marker cube.

include <lib/nested_include.scad>

lib_peg_row(4);
