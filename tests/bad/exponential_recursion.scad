// Recursion that doubles on every level (line 3) and would make 2^40 parts, called on line 4; a good diagnostic stops it within seconds.

module t(n) { if (n > 0) { t(n - 1); t(n - 1); } else cube(1); }
t(40);
