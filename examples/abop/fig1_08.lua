-- Combination of islands and lakes: f moves without drawing, n = 2 (ABOP fig. 1.8).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F+F+F+F",
  steps = 2,
  productions = [[
    F --> F+f-FF+F+FF+Ff+FF-f+FF-F-FF-Ff-FFF
    f --> ffffff
  ]],
  view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
}
