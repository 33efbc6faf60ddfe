tropism: T: 0 1 0 I: 0.5 A: 10
torque: T: 1 0 0 A: 5 E: 1 S: 2
light: O: 1 2 3 P: 0 0 1 10 45 T: 1 0 0
light: A: 1 1 1
