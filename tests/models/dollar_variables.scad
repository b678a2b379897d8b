// Exercises user-defined $-variables: dynamic scoping, so a module sees the caller's $thickness even though it is not a parameter.

$thickness = 2;

module slab(w) {
    cube([w, w, $thickness]);
}

module thick_context() {
    $thickness = 6;
    slab(8);                 // thickness 6, from the caller's dynamic scope
}

slab(10);                                   // thickness 2
translate([20, 0, 0]) thick_context();
translate([40, 0, 0]) slab(5, $thickness = 4);   // passed as an argument: thickness 4
