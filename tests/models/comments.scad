// Exercises comments: line comments, block comments (one and several lines), trailing comments, comments inside expressions and argument lists.

/* A block comment
   spanning several lines, containing code-like text: cube(99); // not code
*/
size = 10; // trailing line comment after an assignment
/* block */ width = /* inside an expression */ 20 /* before the semicolon */;

// a line comment with /* an opening block marker that does not open anything
cube([width, size /* second element */, 5]); // trailing comment after a statement
/** doc-style block comment **/
translate([0, 0, 10]) /* between a transform and its child */ sphere(r = 3);
/*
 * star-prefixed block
 */ cylinder(h = 4, r = 2); /* trailing block comment */
