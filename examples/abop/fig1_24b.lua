-- Bracketed plant: edge rewriting, n = 5, δ = 20° (ABOP fig. 1.24b).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F",
  steps = 5,
  productions = "F --> F[+F]F[-F][F]",
  view = { angle = 20, line_width = 1, color = 8 },
}
