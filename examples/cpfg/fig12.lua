-- A two-dimensional closed contour (cpfg guide §3.2.3, fig. 12), contour sides 32.
-- `a`: the contour file contours/fig12a.con (Appendix B.1): its 12 control points (the
-- first one bigger), the closed B-spline through them and the unit circle, the default
-- contour, for comparison.
-- `b`: the contour at both ends of a straight generalized cylinder:
-- `@#(2) @Gs f(1.2) @Ge(8)`; the contour's first vertex lies along the turtle's up vector.
-- `c`: the circle at the base and the contour at the top only: `@Gs f(1.2) @#(2) @Ge(8)`;
-- the cross-section blends linearly from one into the other. The guide does not print
-- these two strings (they are missing from the text); lengths and strip counts are chosen
-- here. Radius 0.5.
local lsys = require "lsys"
local plot = dofile(lsys.here() .. "/plot.lua")

local view = {
  dir = lsys.here(), contours = { [2] = "contours/fig12a.con" }, contour_sides = 32,
  palette = { "#c99a5b" }, direction = { -0.3, -1, -0.7 },
}

return {
  a = lsys.lsystem {
    axiom = plot.contour(lsys.here() .. "/contours/fig12a.con"),
    view = { palette = { "#1f1f1f", "#9a9a9a", "#c0392b" }, contour_sides = 12 },
  },
  b = lsys.lsystem { axiom = "#(1) @#(2) @Gs f(1.2) @Ge(8)", view = view },
  c = lsys.lsystem { axiom = "#(1) @Gs f(1.2) @#(2) @Ge(8)", view = view },
}
