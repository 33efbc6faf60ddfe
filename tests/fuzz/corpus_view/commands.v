angle factor: 8
initial color: 1
viewpoint: 0,0,1
view reference point: 0,0,0
