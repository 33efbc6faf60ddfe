-- Bracketed plant: node rewriting with apex X, n = 7, δ = 25.7° (ABOP fig. 1.24e).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "X",
  steps = 7,
  productions = [[
    X --> F[+X][-X]FX
    F --> FF
  ]],
  view = { angle = 25.7, line_width = 1.5, color = 8 },
}
