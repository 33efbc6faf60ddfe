angle increment: 30
initial color: 2
initial line width: 3 pixels
