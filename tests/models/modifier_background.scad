// Exercises the % (background) modifier: the translated cube is shown transparent and is not part of the result; the sphere is normal geometry.

sphere(r = 5);
%translate([20, 0, 0]) cube(10);
