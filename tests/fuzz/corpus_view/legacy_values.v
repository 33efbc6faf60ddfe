angle increment: 22.5
color increment: -2 1
initial colour: 7 2
line width increment: 0.25
line style: 2
projection: parallel
twist: -900
