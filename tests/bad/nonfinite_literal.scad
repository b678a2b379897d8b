// A size that is not a finite number: 1e999 overflows to infinity on line 3; a good diagnostic points at 1e999 on line 3.

cube([1e999, 10, 10]);
