-- Curved generalized cylinders (cpfg guide §3.2.2, fig. 10).
-- `a`: `!(0.4) @Gs -(45) f -(45) !(0.2) @Gr(30,4.5,0,3.5) @Ge(20)`: the longitudinal
-- section of fig. 9 mapped onto a bent axis; the bulge follows the curve.
-- `b`: a thicker bent cylinder, drawn as a wireframe in the gallery: the cross-sections are
-- swept along the axis, each perpendicular to it.
-- `c`: the same bend with a radius larger than the radius of curvature of the axis: on the
-- inside of the bend consecutive cross-sections cross each other (an artefact that cpfg does
-- not avoid either). Details of b and c (radii, angles) are not given in the guide.
local lsys = require "lsys"

local palette = { "#c99a5b" }

return {
  a = lsys.lsystem {
    axiom = "!(0.4) @Gs -(45) f -(45) !(0.2) @Gr(30,4.5,0,3.5) @Ge(20)",
    view = { palette = palette, contour_sides = 24, direction = { -0.4, -0.5, -1 } },
  },
  b = lsys.lsystem {
    axiom = "!(0.5) @Gs -(45) f -(45) @Ge(12)",
    view = { palette = palette, contour_sides = 12, direction = { -0.2, -0.3, -1 } },
  },
  c = lsys.lsystem {
    axiom = "!(1.6) @Gs -(60) f -(60) @Ge(12)",
    view = { palette = palette, contour_sides = 12, direction = { 0, 0, -1 } },
  },
}
