// Exercises the ! (root) modifier: only the marked subtree (a translated sphere) is rendered; the cube and the cylinder are ignored.

cube(10);
!translate([0, 0, 20]) sphere(r = 4);
cylinder(h = 10, r = 3);
