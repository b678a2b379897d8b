// Semantic error: call to an unknown module 'cuboid' on line 3 (maybe 'cube'); a good diagnostic names 'cuboid' and points at line 3.

cuboid([10, 20, 30]);
