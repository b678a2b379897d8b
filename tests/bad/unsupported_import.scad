// Unsupported construct: import("x.stl") on line 3 (an external mesh, which also does not exist); a good diagnostic names 'import' at line 3 as unsupported.

import("x.stl");
