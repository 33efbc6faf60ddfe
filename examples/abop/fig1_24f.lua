-- Bracketed plant: node rewriting with apex X, n = 5, δ = 22.5° (ABOP fig. 1.24f).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "X",
  steps = 5,
  productions = [[
    X --> F-[[X]+X]+F[+FX]-X
    F --> FF
  ]],
  view = { angle = 22.5, line_width = 1.5, color = 8 },
}
