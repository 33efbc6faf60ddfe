initial elasticity: 0.5
