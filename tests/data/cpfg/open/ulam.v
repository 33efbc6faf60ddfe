angle increment: 90
