initial line width: 3
contour sides: 3
polygonization level: 0
twist of cylinders: on
background colour: 1,1,1
light direction: 0 0 1
