-- Quadratic Koch island: the edge F replaced by an eight-segment generator (ABOP fig. 1.6).
-- The figure shows n = 0..3; the island after n steps has 4·8^n segments F.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F-F-F-F",
  steps = 3,
  productions = "F --> F-F+F+FF-F-F+F",
  view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
}
