verbose: 1
domain size: 16 16 16
position: -8 -8 -8
grid size: 4x4x4
ray density: 20
spectrum samples: 2
source spectrum: 600 1.0 700 1.0
maximum depth: 4
Russian roulette: 0.5 0.5
reflectance model: blinn
rays from objects: no
leaf material (top): 0.1 0.0 0.0 10.0 1.4
                   : 0.3 0.0 0.5 10.0 1.4
one ray per spectrum: yes
remove objects: on
light source: 0.0 1.0 0.0 1.0
number of runs: 1
