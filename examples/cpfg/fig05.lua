-- A simple generalized cylinder (cpfg guide §3.1, fig. 5): `@Gs f -(45) f @Ge(6)`,
-- one Hermite segment between two control points, swept by a disc of radius 0.2 in 6 strips.
-- Model `a` is the construction (fig. 5a): the turtle path in grey, the control points as
-- spheres and the Hermite curve itself as a very thin cylinder. Model `b` is the cylinder
-- (fig. 5b); the gallery also draws it with `wireframe = true` (fig. 5c): the 6 strips of
-- 8 quadrilaterals each and the flat end caps. Look at how the axis leaves the first point
-- along the turtle heading (up) and reaches the second one heading 45° to the right.
local lsys = require "lsys"

local palette = { "#8c8c8c", "#1f1f1f", "#c99a5b" }   -- grey path, black curve, cylinder

return {
  a = lsys.lsystem {
    axiom = ";(1) #(2) [ F -(45) F ] "                       -- the turtle path
      .. ";(2) [ @O(0.08) f -(45) f @O(0.08) ] "             -- the two control points
      .. "!(0.02) @Gs f -(45) f @Ge(24)",                    -- the curve
    view = { palette = palette, contour_sides = 12 },
  },
  b = lsys.lsystem {
    axiom = ";(3) !(0.4) @Gs f -(45) f @Ge(6)",
    view = { palette = palette },
  },
}
