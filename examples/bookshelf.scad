// A bookshelf: two side panels, a back, evenly spaced shelves in a for loop, and a hanging hole through the back.

width = 80;
depth = 25;
height = 150;
board = 2;          // board thickness
shelves = 5;        // number of shelves, including top and bottom
hole_d = 4;         // hanging hole diameter

inner_w = width - 2 * board;
spacing = (height - board) / (shelves - 1);

// a board given by its size, centered in x and y only when asked
module board(size, centered = false) {
    cube(size, center = centered);
}

// left side panel
board([board, depth, height]);
// right side panel
translate([width - board, 0, 0]) board([board, depth, height]);

// back panel with two hanging holes near the top
difference() {
    // back board
    translate([board, depth - board, 0]) cube([inner_w, board, height]);
    // hanging holes, drilled along y
    for (x = [width / 4, 3 * width / 4])
        translate([x, depth - board / 2, height - 10])
            rotate([90, 0, 0])
                cylinder(h = board + 2, d = hole_d, center = true);
}

// shelves, evenly spaced from the floor to the top
for (i = [0 : shelves - 1])
    translate([board, 0, i * spacing])
        color(i % 2 == 0 ? "peru" : "tan")
            board(size = [inner_w, depth - board, board]);

// kick plate under the bottom shelf, at the front
translate([width / 2, board / 2, 5])
    board([inner_w, board, 6], centered = true);
