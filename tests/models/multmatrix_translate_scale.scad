// Exercises multmatrix with a 4x4 matrix combining scale (2, 3, 4) and translation (10, 20, 30), and a 3x4 matrix (bottom row omitted).

multmatrix([[2, 0, 0, 10],
            [0, 3, 0, 20],
            [0, 0, 4, 30],
            [0, 0, 0, 1]])
    cube(1);                     // a 2 x 3 x 4 box at [10, 20, 30]
multmatrix(m = [[1, 0, 0, -20], [0, 1, 0, 0], [0, 0, 2, 5]])
    cylinder(h = 3, r = 2);      // height 6 starting at z = 5, x = -20
