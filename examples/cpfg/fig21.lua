-- A branch fork drawn with generalized cylinders (cpfg guide §3.4, fig. 21).
-- The string (not printed in the guide; rebuilt from its description) is
--   B F [ +(40) ! F E ] [ -(25) ! F E ]
-- one segment supporting two branches, 40° to the left and 25° to the right, each
-- thinner by the width increment 0.1 (`!`); B marks the base, E the end of each branch.
-- `a`: the segments drawn as straight cylinders (width 0.3, then 0.2).
-- `b`: the parametric curves: the homomorphism
--   B -> @Gs    E -> @Ge(2)    F -> f(0.5) @Gc(4) f(0.5)
-- (the guide prints `@Gb` for B: a misprint for @Gs) puts one control point in the middle
-- of each segment; here thin cylinders show the curves and dots the control points.
-- The second branch starts again from the control point in the middle of the first
-- segment: the active control point is part of the turtle state that `[` saves.
-- `c`: the generalized cylinders of that homomorphism; the gallery draws them as a
-- wireframe (fig. 21c) and shaded (fig. 21d).
local lsys = require "lsys"

local fork = "B F [ +(40) ! F E ] [ -(25) ! F E ]"
local palette = { { diffuse = { 0.55, 0.40, 0.26 }, specular = { 0.2, 0.2, 0.2 },
                    shininess = 20 }, "#1f1f1f", "#c0392b" }

return {
  a = lsys.lsystem {
    axiom = fork,
    view = { line_style = "cylinder", line_width = 0.3, width_increment = 0.1,
             contour_sides = 24, palette = palette },
  },
  b = lsys.lsystem {
    axiom = fork,
    homomorphism = [[
      B --> ;(2) #(0.03) @Gs [ ;(3) @O(0.07) ]
      E --> @Ge(2) [ ;(3) @O(0.07) ]
      F --> f(0.5) @Gc(4) [ ;(3) @O(0.07) ] f(0.5)
    ]],
    view = { width_increment = 0, contour_sides = 12, palette = palette },
  },
  c = lsys.lsystem {
    axiom = fork,
    homomorphism = [[
      B --> @Gs
      E --> @Ge(2)
      F --> f(0.5) @Gc(4) f(0.5)
    ]],
    view = { line_width = 0.3, width_increment = 0.1, contour_sides = 16, palette = palette },
  },
}
