0 6 0 6 0 0.1
PRECISION S: 3 T: 3
CONTACT POINT X: 3 Y: 0 Z: 0
END POINT X: 3 Y: 6 Z: 0
HEADING X: 0 Y: 1 Z: 0
UP X: 0 Y: 0 Z: 1
SIZE: 6
a
TOP COLOR: 1 DIFFUSE: 0.5 BOTTOM COLOR: 2 DIFFUSE: 0.5
AL: ~ A: ~ AR: ~
L: ~ R: b
BL: ~ B: c BR: d
0 0 0  1 0 0.1  2 0 0  3 0 0.1
0 1 0  1 1 0.1  2 1 0  3 1 0.1
0 2 0  1 2 0.1  2 2 0  3 2 0.1
0 3 0  1 3 0.1  2 3 0  3 3 0.1
b
TOP COLOR: 1 DIFFUSE: 0.5 BOTTOM COLOR: 2 DIFFUSE: 0.5
AL: ~ A: ~ AR: ~
L: a R: ~
BL: c B: d BR: ~
3 0 0.1  4 0 0  5 0 0.1  6 0 0
3 1 0.1  4 1 0  5 1 0.1  6 1 0
3 2 0.1  4 2 0  5 2 0.1  6 2 0
3 3 0.1  4 3 0  5 3 0.1  6 3 0
c
TOP COLOR: 1 DIFFUSE: 0.5 BOTTOM COLOR: 2 DIFFUSE: 0.5
AL: ~ A: a AR: b
L: ~ R: d
BL: ~ B: ~ BR: ~
0 3 0  1 3 0.1  2 3 0  3 3 0.1
0 4 0  1 4 0.1  2 4 0  3 4 0.1
0 5 0  1 5 0.1  2 5 0  3 5 0.1
0 6 0  1 6 0.1  2 6 0  3 6 0.1
d
TOP COLOR: 1 DIFFUSE: 0.5 BOTTOM COLOR: 2 DIFFUSE: 0.5
AL: a A: b AR: ~
L: c R: ~
BL: ~ B: ~ BR: ~
3 3 0.1  4 3 0  5 3 0.1  6 3 0
3 4 0.1  4 4 0  5 4 0.1  6 4 0
3 5 0.1  4 5 0  5 5 0.1  6 5 0
3 6 0.1  4 6 0  5 6 0.1  6 6 0
