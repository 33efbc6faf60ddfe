-- The snake kolam curve (cpfg guide §3.1, fig. 7), n = 2, δ = 90°.
-- `a`: drawn with lines, axiom F X + F + F X + F.
-- `b`: drawn as one closed generalized cylinder: the homomorphism puts one control point in
-- the middle of every segment (F -> f @Gc(4) f), G starts the cylinder, and the extra `+ F`
-- at the end of the axiom adds a last control point on top of the first, closing the loop.
-- The corners of the line drawing become smooth arcs. Radius 0.25 (line width 0.5), half
-- an F step of the cylinder; the G of the axiom is only half a segment long.
local lsys = require "lsys"

local rule = "X --> X - F - F + F X + F + F X - F - F + F X"

return {
  a = lsys.lsystem {
    axiom = "F X + F + F X + F",
    steps = 2,
    productions = rule,
    view = { angle = 90, line_width = 2, palette = { "#24426e" } },
  },
  b = lsys.lsystem {
    axiom = "G X + F + F X + F + F",
    steps = 2,
    productions = rule,
    homomorphism = [[
      G --> @Gs f
      F --> f @Gc(4) f
    ]],
    view = { angle = 90, line_width = 0.5, contour_sides = 12, palette = { "#c99a5b" },
             direction = { 0, -0.5, -1 } },
  },
}
