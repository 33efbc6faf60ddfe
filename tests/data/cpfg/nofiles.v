texture: F: gone.rgb H: l L: l
texture: F: ../views/leaf.png
surface: b bract.s 1.5
surface: l ../views/leaf.s 1 2
