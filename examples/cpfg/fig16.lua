-- A long leaf blade with an open contour (cpfg guide §3.2.3, fig. 16).
-- `a`: the open contour contours/fig16a.con (Appendix B.1): 15 control points, the first
-- and last repeated three times so the B-spline starts and ends on them; the unit circle
-- for comparison.
-- `b`, `c`: the blade, from the string printed in the guide:
--   -(40) @#(2) @Gs -(90) f(10) @Gr(1) @Gr(20,1.5,-20,1.5) @Gt(2,1) -(50) @Ge(20)
-- one curved segment of length 10 whose radius bulges (radius tangents 20° and -20°, kept
-- at those angles on the long segment by @Gr(1)) from 0.05 at both ends (line width 0.1,
-- not given in the guide) to about 1.4 in the middle; the wide direction of the contour
-- lies along the turtle's up vector, across the plane of the bend. `b` is seen from the
-- front (the plane of the bend), `c` from above and to the side, showing the open,
-- slightly wavy cross-section.
local lsys = require "lsys"
local plot = dofile(lsys.here() .. "/plot.lua")

local blade = "-(40) @#(2) @Gs -(90) f(10) @Gr(1) @Gr(20,1.5,-20,1.5) @Gt(2,1) -(50) @Ge(20)"

local function view (direction)
  return { dir = lsys.here(), contours = { [2] = "contours/fig16a.con" }, contour_sides = 32,
           line_width = 0.1, direction = direction,
           palette = { { diffuse = { 0.36, 0.58, 0.22 }, specular = { 0.2, 0.2, 0.2 },
                         shininess = 25 } } }
end

return {
  a = lsys.lsystem {
    axiom = plot.contour(lsys.here() .. "/contours/fig16a.con"),
    view = { palette = { "#1f1f1f", "#9a9a9a", "#c0392b" }, contour_sides = 12 },
  },
  b = lsys.lsystem { axiom = blade, view = view { 0, 0, -1 } },
  c = lsys.lsystem { axiom = blade, view = view { 0.8, -0.9, -0.5 } },
}
