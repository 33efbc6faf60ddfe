-- A three-dimensional closed contour (cpfg guide §3.2.3, fig. 13), contour sides
-- 32. contours/fig13a.con is the contour of fig. 12 with a third coordinate: 1 at the first
-- control point, 0 elsewhere. The third coordinate runs along the turtle heading, so near
-- that point the cross-section bends up the axis: a pointed tongue.
-- `a`: the contour in perspective: control points, B-spline, the unit circle.
-- `b`: the contour at both ends, `@#(2) @Gs f(1.2) @Ge(8)`: a tongue at the base, inside the
-- cylinder, and one on the top; `c`: the circle at the base and the contour at the top,
-- `@Gs f(1.2) @#(2) @Ge(8)` (the strings of fig. 12; radius 0.5).
local lsys = require "lsys"
local plot = dofile(lsys.here() .. "/plot.lua")

local view = {
  dir = lsys.here(), contours = { [2] = "contours/fig13a.con" }, contour_sides = 32,
  palette = { "#c99a5b" }, direction = { -0.3, -1, -0.7 },
}

return {
  a = lsys.lsystem {
    axiom = plot.contour(lsys.here() .. "/contours/fig13a.con"),
    view = { palette = { "#1f1f1f", "#9a9a9a", "#c0392b" }, contour_sides = 12,
             direction = { 0.5, -0.4, -1 } },
  },
  b = lsys.lsystem { axiom = "#(1) @#(2) @Gs f(1.2) @Ge(8)", view = view },
  c = lsys.lsystem { axiom = "#(1) @Gs f(1.2) @#(2) @Ge(8)", view = view },
}
