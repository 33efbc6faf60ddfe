/* Older cpfg commands: angle increment, a two-sided colour, pixel lines,
   polygonization level, OpenGL lights and the single tropism of early versions. */
angle increment: 22.5
initial color: 3 3
initial line width: 2 pixels
polygonization level: 3
light: V: 5 3 1 D: 1.3 1.5 1.3
light: V: -1 -1 0
tropism direction: 0,-2,0
initial elasticity: 0.05
elasticity increment: 0.01
surface: c calyx.s 2.0
