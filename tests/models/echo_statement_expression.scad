// Exercises echo as a statement and as an expression (echo(...) expr evaluates to expr) used inside a size.

size = 6;
echo("size is", size);
echo(s = size, double = size * 2);
h = echo("computing h") size + 4;        // 10
cube([size, size, h]);
translate([10, 0, 0]) cylinder(h = echo(h = h) h, r = 2);
