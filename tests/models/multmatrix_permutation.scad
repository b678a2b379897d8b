// Exercises multmatrix with a permutation matrix (axes cycled: new x = old y, new y = old z, new z = old x) and one that swaps x and y.

multmatrix([[0, 1, 0, 0],
            [0, 0, 1, 0],
            [1, 0, 0, 0],
            [0, 0, 0, 1]])
    cube([2, 4, 6]);             // a 4 x 6 x 2 box
translate([20, 0, 0])
    multmatrix([[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
        cylinder(h = 5, r = 1);  // a reflection, the cylinder is unchanged in shape
