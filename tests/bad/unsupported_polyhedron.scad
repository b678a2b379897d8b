// Unsupported construct: polyhedron on line 3 (a tetrahedron); a good diagnostic names 'polyhedron' at line 3 as unsupported.

polyhedron(points = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]],
           faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);
