/* A view file in cpfg's syntax with every command lsys reads (tests/viewfile_spec.lua
   checks the table it loads to). Unsupported commands at the end only warn. */
angle factor: 16
initial color: 2
color increment: 3
initial line width: 0.5 polygons
line width increment: 0.1
line style: cylinder
viewpoint: 0,10,30
view reference point: 0, 5, 0
twist: 150
projection: perspective
viewing angle: 40
light direction: 1,2,3
background color: 0.1,0.2,0.3
contour: 1 leaf.con
contour: 2 sub/stem.con    // a path relative to this file
contour sides: 12
twist of cylinders: on
texture: F: bark.png H: l L: n E: d
texture: F: leaf.png H:n L:l E:m S:   /* mapped onto whole surfaces */
tropism: T: 0,-1,0 A: 30 E: 0.2 S: 0.05
torque:  T: 0.0 1.0 0.0 E: 0.1
tropism: T: 1 0 0
surface: P petal.s 2.5
surface: L leaf.s 1 8 4 2

z buffer: on
front distance: -100
render mode: shaded
