// Nothing to draw: the file only assigns a variable (a = 1 on line 3) and creates no geometry; a good diagnostic says the model produces no primitives.

a = 1;
