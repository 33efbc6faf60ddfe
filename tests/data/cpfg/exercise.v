angle increment: ?
initial color: 2
