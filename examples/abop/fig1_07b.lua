-- Quadratic snowflake curve, n = 4 (ABOP fig. 1.7b).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "-F",
  steps = 4,
  productions = "F --> F+F-F-F+F",
  view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
}
