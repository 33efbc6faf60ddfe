-- Stochastic branching structure: each F picks one of three successors (ABOP fig. 1.27).
-- Weights as printed (.33, .33, .34); n = 5 and δ = 25.7° as in fig. 1.24a, whose rule is the
-- first alternative. Change `seed` for a different specimen; each seed is reproducible.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F",
  steps = 5,
  seed = 1,
  productions = [[
    F --> F[+F]F[-F]F : 0.33
    F --> F[+F]F      : 0.33
    F --> F[-F]F      : 0.34
  ]],
  view = { angle = 25.7, line_width = 1, color = 8 },
}
