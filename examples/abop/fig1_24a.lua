-- Bracketed plant: axial tree by edge rewriting, n = 5, δ = 25.7° (ABOP fig. 1.24a).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F",
  steps = 5,
  productions = "F --> F[+F]F[-F]F",
  view = { angle = 25.7, line_width = 1, color = 8 },
}
