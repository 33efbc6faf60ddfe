-- Quadratic Koch island with an 18-segment generator, n = 2 (ABOP fig. 1.7a).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F-F-F-F",
  steps = 2,
  productions = "F --> F+FF-FF-F-F+F+FF-F-F+F+FF+FF-F",
  view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
}
