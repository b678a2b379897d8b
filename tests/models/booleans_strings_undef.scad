// Exercises booleans, strings and undef as values: tests with is_undef/is_string/is_bool, string comparison, undef default, booleans picking sizes.

flag = true;
off = false;
name = "plate";
nothing = undef;

w = flag ? 10 : 1;                      // 10
d = off ? 1 : 20;                       // 20
t = is_undef(nothing) ? 3 : 99;         // 3
k = (name == "plate") ? 2 : 7;          // 2
s = is_string(name) && is_bool(flag) ? 4 : 0;   // 4
cube([w, d, t]);
translate([0, 0, 10]) cube([k, s, undef == nothing ? 1 : 5]);
