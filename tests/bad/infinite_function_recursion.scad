// Recursion error: function 'f' calls itself with no base case on line 3, so evaluation never ends; a good diagnostic reports recursion too deep in 'f', pointing at line 3 (the call on line 5 is where it started).

function f(n) = f(n + 1) + 1;

cube(f(1));
