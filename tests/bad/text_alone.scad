// Unsupported construct: text("hi") on line 3 used directly (no extrusion), a 2-D primitive; a good diagnostic names 'text' at line 3 as unsupported.

text("hi");
