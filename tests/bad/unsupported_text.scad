// Unsupported construct: text("hi") on line 3 (2-D text, here extruded); a good diagnostic names 'text' at line 3 as unsupported.

linear_extrude(2) text("hi");
