-- Bracketed plant: node rewriting with apex X, n = 7, δ = 20° (ABOP fig. 1.24d).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "X",
  steps = 7,
  productions = [[
    X --> F[+X]F[-X]+X
    F --> FF
  ]],
  view = { angle = 20, line_width = 1.5, color = 8 },
}
