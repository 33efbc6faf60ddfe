angle increment: 90
initial color: 1
