0 3 0 3 -0.5 0.5
CONTACT POINT X: 1 Y: 0 Z: 0
END POINT X: 0.3 Y: 2 Z: 0.4
HEADING X: 0 Y: 1 Z: 0
UP X: 0.6 Y: 0 Z: -0.8
SIZE: 3
a
TOP COLOR: 1 DIFFUSE: 0.5 BOTTOM COLOR: 2 DIFFUSE: 0.5
AL: ~ A: ~ AR: ~
L: ~ R: ~
BL: ~ B: ~ BR: ~
0 0 0  1 0 0.5  2 0 0  3 0 -0.5
0 1 0  1 1 0.5  2 1 0  3 1 -0.5
0 2 0  1 2 0.5  2 2 0  3 2 -0.5
0 3 0  1 3 0.5  2 3 0  3 3 -0.5
