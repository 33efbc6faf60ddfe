line style: cylinder
contour sides: 10
light direction: 0.5,1.0,0.8
projection: parallel
