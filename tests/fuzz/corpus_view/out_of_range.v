viewing angle: 179.5
background color: 2,0,0
contour: 65535 c.con
tropism direction: 1,0,0
elasticity increment: 0.1
