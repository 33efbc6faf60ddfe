angle increment: 90
initial color: 1
line style: cylinder
initial line width: 3
