// Unsupported construct: linear_extrude on line 3 (of a 2-D circle); a good diagnostic names 'linear_extrude' at line 3 as unsupported.

linear_extrude(height = 10) circle(r = 5);
